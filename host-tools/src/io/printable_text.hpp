// SPDX-License-Identifier: MIT
#pragma once
// User text quoted in a message (a cell, a column name, an option's value), made safe to print on one
// line: control characters, invisible and direction-changing Unicode characters and bytes that are not
// UTF-8 are written as escapes (\0, \t, \x1b, \u200b, \ufeff, \xff), so that what the message shows is
// what the file holds (a zero-width space in a column name printed raw looked like a name that matched;
// a NUL byte cut the message short), and the text is cut after a bounded number of characters (a huge
// single token made an error line of 689 KB). Printable UTF-8 (accents, symbols) is kept as it is.
#include <cstddef>
#include <string>
#include <string_view>

namespace jacobid::io {

// How many characters of a piece of user text a message quotes.
constexpr std::size_t kQuotedTextChars = 80;
// How many characters a whole message may have (the command line's last safety net).
constexpr std::size_t kMessageChars = 2000;

// `text` escaped, cut after max_chars characters (escapes count as one) with "..." appended when cut.
std::string printable_text(std::string_view text, std::size_t max_chars = kQuotedTextChars);

// A whole message for the terminal: escaped like printable_text, and when longer than kMessageChars
// characters, its start and end around " ... (N characters left out) ... ".
std::string printable_message(std::string_view message);

}  // namespace jacobid::io
