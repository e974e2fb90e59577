#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Boots Debian's stock kernel under qemu (TCG, no KVM) with a busybox initramfs that holds the test
binaries and one scenario script, and turns what the serial console says into an exit status:
0 = the scenario printed PASS, 1 = it printed FAIL, 2 = no verdict (the VM did not boot, hung, or
crashed: a failure too, bounded by --timeout).

Assets (scripts/vm-deps.sh): <assets>/<arch>/vmlinuz, busybox (static), modules/ (the CAN modules).
Scenario (tests/vm/scenarios/*.sh): a busybox sh script run by /init as root in /tmp, with header lines
    # modules: can can-raw vcan        kernel modules to load, dependencies first (resolved as well)
    # binaries: test_hal_vcan ...      names given with --bin NAME=PATH, installed as /bin/NAME
    # dynamic: jacobid jacobid-fw      the same, dynamically linked: installed with every shared library
                                       they load and the ELF interpreter (see below)
    # include: chain-lib.sh            files beside the scenario, installed as /scenario-lib/NAME (to source)
    # memory: 1024   # smp: 2          qemu -m / -smp unless given on the command line (default 512 / 1)
    # qemu: -icount shift=1            more qemu options (after the harness's own)
    # cmdline: preempt=full            more kernel command line
    # host: identify-on-host.sh        a bash script beside the scenario, run on the build machine after the
                                       guest passed (the verdict is then its exit status), in the directory
                                       of the files the guest exported, with JACOBID=--host-jacobid in its
                                       environment: work that needs the PC's tools (identification)
A guest exports a file by printing "JACOBID-VM-FILE-BEGIN name", the file gzip-compressed in base64 lines, and
"JACOBID-VM-FILE-END name" (tests/vm/scenarios/chain-lib.sh export_files); the harness writes it to
<work>/<arch>-<scenario>.files/name.
Its exit status is the verdict. `binaries` must be static. `dynamic` ones: without --libdir (a native
build for the VM's architecture) `ldd` resolves their libraries on the build machine and each goes to the
same path in the VM; with --libdir DIR... (a cross build: the target's sysroot and cross C library) the
DT_NEEDED entries are resolved recursively in those directories (readelf), the libraries go to
/usr/lib/jacobid-vm (on LD_LIBRARY_PATH in the VM) and the interpreter to its PT_INTERP path.
"""
import argparse
import base64
import gzip
import io
import os
import re
import shutil
import stat
import subprocess
import sys
import threading
import time

QEMU = {
    "x86_64": (["qemu-system-x86_64", "-accel", "tcg", "-cpu", "max"], "ttyS0"),
    "aarch64": (["qemu-system-aarch64", "-M", "virt", "-cpu", "cortex-a72", "-accel", "tcg"], "ttyAMA0"),
}
MARK = "JACOBID-VM:"
FILE_BEGIN, FILE_END = "JACOBID-VM-FILE-BEGIN ", "JACOBID-VM-FILE-END "


class ExportedFiles:
    """The files a guest prints on its console between FILE_BEGIN and FILE_END, written to `directory`."""

    def __init__(self, directory):
        self.directory = directory
        shutil.rmtree(directory, ignore_errors=True)  # a previous run's files are not this run's
        self.name = None
        self.lines = []
        self.written = []

    def take(self, line):
        """True if the console line belongs to an exported file (and is not to be shown)."""
        if line.startswith(FILE_BEGIN):
            self.name, self.lines = os.path.basename(line[len(FILE_BEGIN):].strip()), []
            return True
        if self.name is None:
            return False
        if line.startswith(FILE_END):
            try:
                data = gzip.decompress(base64.b64decode("".join(self.lines), validate=True))
            except (ValueError, OSError, EOFError) as e:  # a console line mangled, e.g. a kernel message inside
                print(f"vm: exported file {self.name} is corrupt ({e}); left out", flush=True)
            else:
                os.makedirs(self.directory, exist_ok=True)
                with open(os.path.join(self.directory, self.name), "wb") as f:
                    f.write(data)
                self.written.append(self.name)
            self.name = None
            return True
        self.lines.append(line.strip())
        return True


class Cpio:
    """newc archive writer: device nodes and root ownership without being root."""

    def __init__(self):
        self.out = io.BytesIO()
        self.ino = 1

    def _entry(self, name, mode, data=b"", rdev=(0, 0)):
        fields = [self.ino, mode, 0, 0, 1, 0, len(data), 0, 0, rdev[0], rdev[1], len(name) + 1, 0]
        self.ino += 1
        self.out.write(b"070701" + b"".join(b"%08X" % f for f in fields) + name.encode() + b"\0")
        self.out.write(b"\0" * (-self.out.tell() % 4))
        self.out.write(data)
        self.out.write(b"\0" * (-self.out.tell() % 4))

    def dir(self, name):
        self._entry(name, stat.S_IFDIR | 0o755)

    def file(self, name, data, mode=0o755):
        self._entry(name, stat.S_IFREG | mode, data)

    def symlink(self, name, target):
        self._entry(name, stat.S_IFLNK | 0o777, target.encode())

    def chardev(self, name, major, minor):
        self._entry(name, stat.S_IFCHR | 0o600, rdev=(major, minor))

    def finish(self):
        self._entry("TRAILER!!!", 0)
        return self.out.getvalue()


INIT = r"""#!/bin/busybox sh
/bin/busybox --install -s /bin
export PATH=/bin HOME=/tmp LD_LIBRARY_PATH=/usr/lib/jacobid-vm
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t tmpfs tmp /tmp
exec </dev/console >/dev/console 2>&1
echo "MARK booted $(uname -r) $(uname -m) in $(cut -d' ' -f1 /proc/uptime) s"
for m in $(cat /etc/modules-load); do
  insmod "/lib/modules/$m" || echo "MARK insmod $m failed"
done
ip link set lo up
cd /tmp
sh /scenario.sh
rc=$?
if [ "$rc" -eq 0 ]; then echo "MARK PASS"; else echo "MARK FAIL (scenario exit $rc)"; fi
echo "MARK finished at $(cut -d' ' -f1 /proc/uptime) s"
sync
poweroff -f
""".replace("MARK", MARK)


def scenario_header(text, key):
    m = re.search(r"^#[ \t]*%s:[ \t]*(.*)$" % key, text, re.M)
    return m.group(1).split() if m else []


def module_depends(path):
    with open(path, "rb") as f:
        data = f.read()
    m = re.search(rb"(?:^|\0)depends=([^\0]*)\0", data)
    return [d for d in m.group(1).decode().split(",") if d] if m else []


def resolve_modules(moddir, names):
    """Module files in load order (dependencies first)."""
    index = {}
    for dirpath, _, files in os.walk(moddir):
        for f in files:
            if f.endswith(".ko"):
                index[f[:-3].replace("_", "-")] = os.path.join(dirpath, f)
    order = []

    def visit(name):
        key = name.replace("_", "-")
        if key not in index:
            sys.exit(f"vm: module {name} not found in {moddir}")
        if index[key] in order:
            return
        for dep in module_depends(index[key]):
            visit(dep)
        order.append(index[key])

    for n in names:
        visit(n)
    return order


def build_initramfs(args, scenario_text):
    assets = os.path.join(args.assets, args.arch)
    c = Cpio()
    for d in ["bin", "dev", "etc", "lib", "lib/modules", "proc", "sys", "tmp", "run"]:
        c.dir(d)
    c.chardev("dev/console", 5, 1)
    c.chardev("dev/null", 1, 3)
    with open(os.path.join(assets, "busybox"), "rb") as f:
        c.file("bin/busybox", f.read())
    c.symlink("bin/sh", "busybox")
    mods = resolve_modules(os.path.join(assets, "modules"), scenario_header(scenario_text, "modules"))
    for path in mods:
        with open(path, "rb") as f:
            c.file("lib/modules/" + os.path.basename(path), f.read(), 0o644)
    c.file("etc/modules-load", "".join(os.path.basename(p) + "\n" for p in mods).encode(), 0o644)
    given = dict(b.split("=", 1) for b in args.bin)
    for name in scenario_header(scenario_text, "binaries"):
        if name not in given:
            sys.exit(f"vm: the scenario needs --bin {name}=PATH")
        with open(given[name], "rb") as f:
            data = f.read()
        machine = {"x86_64": 62, "aarch64": 183}[args.arch]
        if data[:4] == b"\x7fELF" and int.from_bytes(data[18:20], "little") != machine:
            sys.exit(f"vm: {given[name]} is not an {args.arch} executable")
        if _is_dynamic(data):
            sys.exit(f"vm: {given[name]} is dynamically linked; the VM image has no C library (link with -static, or list it under '# dynamic:')")
        c.file("bin/" + name, data)
    dynamic = scenario_header(scenario_text, "dynamic")
    made = {"bin", "dev", "etc", "lib", "lib/modules", "proc", "sys", "tmp", "run"}
    for name in dynamic:
        if name not in given:
            sys.exit(f"vm: the scenario needs --bin {name}=PATH")
        with open(given[name], "rb") as f:
            data = f.read()
        machine = {"x86_64": 62, "aarch64": 183}[args.arch]
        if data[:4] != b"\x7fELF" or int.from_bytes(data[18:20], "little") != machine:
            sys.exit(f"vm: {given[name]} is not an {args.arch} executable")
        c.file("bin/" + name, data)
    executables = [given[n] for n in dynamic]
    libs = target_libraries(executables, args.libdir) if args.libdir else [(p, p) for p in shared_libraries(executables)]
    for lib, dest in libs:
        parts = dest.strip("/").split("/")
        for i in range(1, len(parts)):
            d = "/".join(parts[:i])
            if d not in made:
                c.dir(d)
                made.add(d)
        with open(lib, "rb") as f:  # the file itself where the path is a symlink
            c.file("/".join(parts), f.read())
    includes = scenario_header(scenario_text, "include")
    if includes:
        c.dir("scenario-lib")
    for name in includes:
        with open(os.path.join(os.path.dirname(os.path.abspath(args.scenario)), name), "rb") as f:
            c.file("scenario-lib/" + name, f.read(), 0o644)
    c.file("init", INIT.encode())
    c.file("scenario.sh", scenario_text.encode())
    return gzip.compress(c.finish(), compresslevel=1), [os.path.basename(p) for p in mods]


def shared_libraries(executables):
    """Every shared library and ELF interpreter the executables load, as `ldd` resolves them here."""
    libs = []
    for exe in executables:
        r = subprocess.run(["ldd", exe], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0 or "=>" not in r.stdout:
            sys.exit(f"vm: ldd {exe} failed (static, or not runnable on this machine?):\n{r.stdout}")
        for line in r.stdout.splitlines():
            if "not found" in line:
                sys.exit(f"vm: {exe}: shared library {line.split()[0]} not found")
            m = re.match(r"\s*(?:\S+\s+=>\s+)?(/\S+)\s+\(0x", line)  # "libm.so.6 => /lib/.. (0x..)", "/lib64/ld-.. (0x..)"
            if m and m.group(1) not in libs:
                libs.append(m.group(1))
    return libs


def target_libraries(executables, libdirs):
    """(source, VM path) of every library and the interpreter the executables load, resolved in libdirs
    from the ELF's DT_NEEDED entries (no ldd: a cross build's executables do not run here)."""
    found, todo, interp = {}, list(executables), None
    while todo:
        elf = todo.pop()
        dyn = subprocess.run(["readelf", "-d", "-l", "-W", elf], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if dyn.returncode != 0:
            sys.exit(f"vm: readelf {elf} failed:\n{dyn.stdout}")
        m = re.search(r"Requesting program interpreter: (/[^\]]+)\]", dyn.stdout)
        if m and interp is None:
            interp = m.group(1)
        for soname in re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", dyn.stdout):
            if soname in found:
                continue
            path = next((os.path.join(d, soname) for d in libdirs if os.path.exists(os.path.join(d, soname))), None)
            if path is None:
                sys.exit(f"vm: {elf}: shared library {soname} not found in {' '.join(libdirs)}")
            found[soname] = os.path.realpath(path)
            todo.append(found[soname])
    libs = [(path, "/usr/lib/jacobid-vm/" + soname) for soname, path in sorted(found.items())]
    if interp:
        name = os.path.basename(interp)
        path = next((os.path.join(d, name) for d in libdirs if os.path.exists(os.path.join(d, name))), None)
        if path is None:
            sys.exit(f"vm: the ELF interpreter {interp} is not in {' '.join(libdirs)}")
        libs.append((os.path.realpath(path), interp))
    return libs


def _is_dynamic(elf):
    """True when the ELF has a PT_INTERP program header."""
    import struct
    if elf[:4] != b"\x7fELF":
        return False
    is64, little = elf[4] == 2, elf[5] == 1
    e = "<" if little else ">"
    if is64:
        phoff, = struct.unpack_from(e + "Q", elf, 0x20)
        phentsize, phnum = struct.unpack_from(e + "HH", elf, 0x36)
    else:
        phoff, = struct.unpack_from(e + "I", elf, 0x1C)
        phentsize, phnum = struct.unpack_from(e + "HH", elf, 0x2A)
    return any(struct.unpack_from(e + "I", elf, phoff + i * phentsize)[0] == 3 for i in range(phnum))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--arch", required=True, choices=sorted(QEMU))
    p.add_argument("--assets", required=True)
    p.add_argument("--scenario", required=True)
    p.add_argument("--bin", action="append", default=[], metavar="NAME=PATH")
    p.add_argument("--libdir", action="append", default=[], metavar="DIR",
                   help="target library directory for '# dynamic:' executables of a cross build (repeatable)")
    p.add_argument("--work", required=True, help="directory for the initramfs and the console log")
    p.add_argument("--timeout", type=float, default=300.0, help="seconds from start to power-off")
    p.add_argument("--memory", help="MiB (default: the scenario's '# memory:' header, else 512)")
    p.add_argument("--smp", help="CPUs (default: the scenario's '# smp:' header, else 1)")
    p.add_argument("--quiet", action="store_true", help="print only the scenario's lines and the verdict")
    p.add_argument("--host-jacobid", help="the build machine's jacobid, for a scenario's '# host:' step")
    args = p.parse_args()

    assets = os.path.join(args.assets, args.arch)
    if not os.path.exists(os.path.join(assets, "vmlinuz")):
        print(f"vm: no kernel in {assets}: run scripts/vm-deps.sh first", file=sys.stderr)
        return 2
    with open(args.scenario) as f:
        scenario_text = f.read()
    args.memory = args.memory or (scenario_header(scenario_text, "memory") or ["512"])[0]
    args.smp = args.smp or (scenario_header(scenario_text, "smp") or ["1"])[0]
    name = os.path.splitext(os.path.basename(args.scenario))[0]
    os.makedirs(args.work, exist_ok=True)
    initrd = os.path.join(args.work, f"{args.arch}-{name}.cpio.gz")
    log_path = os.path.join(args.work, f"{args.arch}-{name}.console.log")
    image, mods = build_initramfs(args, scenario_text)
    with open(initrd, "wb") as f:
        f.write(image)

    qemu, console = QEMU[args.arch]
    cmd = qemu + ["-m", args.memory, "-smp", args.smp, "-nographic", "-no-reboot", "-monitor", "none",
                  "-kernel", os.path.join(assets, "vmlinuz"), "-initrd", initrd,
                  "-append", " ".join([f"console={console} panic=-1 quiet loglevel=3"] + scenario_header(scenario_text, "cmdline"))] + scenario_header(scenario_text, "qemu")
    print(f"vm: {args.arch} {name}: {len(image) // 1024} KiB initramfs, modules {' '.join(mods) or '-'}; "
          f"console log {log_path}", flush=True)
    host_step = scenario_header(scenario_text, "host")
    if host_step and not args.host_jacobid:
        print(f"vm: {args.arch} {name}: the scenario's host step ({host_step[0]}) needs --host-jacobid PATH", file=sys.stderr)
        return 2
    exported = ExportedFiles(os.path.join(args.work, f"{args.arch}-{name}.files"))
    start = time.monotonic()
    verdict = None
    with open(log_path, "w") as log:
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        timer = threading.Timer(args.timeout, proc.kill)
        timer.start()
        try:
            for raw in proc.stdout:
                line = raw.decode(errors="replace").rstrip("\r\n")
                log.write(line + "\n")
                if exported.take(line):
                    continue
                if MARK in line:
                    m = re.search(MARK + r" (PASS|FAIL.*)$", line)
                    if m and verdict is None:
                        verdict = m.group(1)
                if not args.quiet or MARK in line or re.search(r"^\[ *(OK|FAILED|PASSED|SKIPPED) *\]|Failure|\.cpp:\d+", line):
                    print(f"  [{args.arch} {time.monotonic() - start:6.1f}s] {line}", flush=True)
        finally:
            proc.wait()
            timer.cancel()
    elapsed = time.monotonic() - start
    if verdict is None:
        why = "timed out" if elapsed >= args.timeout else f"qemu exited with {proc.returncode}"
        print(f"vm: {args.arch} {name}: NO VERDICT ({why} after {elapsed:.0f} s; did the VM boot?) - see {log_path}")
        return 2
    print(f"vm: {args.arch} {name}: {verdict} in {elapsed:.0f} s")
    if verdict != "PASS":
        return 1
    if host_step:
        return run_host_step(args, name, host_step[0], exported)
    return 0


def run_host_step(args, name, script, exported):
    """The scenario's '# host:' script, in the directory of the exported files; its exit status is the verdict."""
    path = os.path.join(os.path.dirname(os.path.abspath(args.scenario)), script)
    os.makedirs(exported.directory, exist_ok=True)
    env = dict(os.environ, JACOBID=os.path.abspath(args.host_jacobid))
    print(f"vm: {args.arch} {name}: host step {script} on {', '.join(exported.written) or 'no exported files'} "
          f"in {exported.directory}", flush=True)
    proc = subprocess.run(["bash", path], cwd=exported.directory, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT)
    for line in proc.stdout.decode(errors="replace").splitlines():
        print(f"  [host] {line}", flush=True)
    verdict = "PASS" if proc.returncode == 0 else f"FAIL (host step exit {proc.returncode})"
    print(f"vm: {args.arch} {name}: host step {verdict}")
    return 0 if proc.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
