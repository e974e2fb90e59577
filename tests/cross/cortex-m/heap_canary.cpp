// SPDX-License-Identifier: MIT
// Negative control for the no-heap link: this must NOT link (operator new -> malloc is unavailable).
// The pointer escapes to a volatile global so that the compiler cannot elide the allocation.
int* volatile g_escape;

int main() {
    g_escape = new int[16];
    return 0;
}
