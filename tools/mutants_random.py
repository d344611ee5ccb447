#!/usr/bin/env python3
"""Random mutants for tools/mutants --random (see its --help).

Generates mutants at random sites of one folder's C++ sources with a fixed set of operators, builds
each in the scratch tree tools/mutants uses, runs the folder's test family and reports killed,
survived, did not build and timed out. The same seed gives the same mutants for the same sources, and
an edit changes the choice only at the sites it touches (choose()).
A survivor is either killed by a new test or named in FOLDER/mutants.equivalent with the reason.
"""
import argparse
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Tests that run the whole player (or its package) rather than one component's test program.
END_TO_END = re.compile(r"^(cli|service)\.")

# The test family of each folder: the ctest tests that exercise its code.
FAMILIES = {
    "player/platform": r"^(gl|cli)\.",
    "player/gl": r"^gl\.",
    "player/scene": r"^(unit|gl)\.",
    "player/render": r"^(unit|gl)\.",
    "player/playback": r"^(unit|cli)\.",
    "player/app": r"^(unit|gl|cli|service)\.",
    "player/ssao": r"^(unit|gl|aoref)\.",
    "player/base": r"^(unit|hal|cli)\.",
    "hal": r"^(hal|unit)\.",
    "lightfield": r"^(unit|gl)\.",
}

# Where the fast suite cannot reach a folder's code (the kms backend; hal's GPIO, V4L2 and evdev
# backends), the vm tier's guests do. Their tests run last, for a mutant that every fast test let
# through, one guest at a time and the shortest first, each only when its programs hold the file.
VM_FAMILIES = {
    "player/platform": ["vm.kms_play", "vm.board_play", "vm.kms_hotplug"],
    "hal": ["vm.hal_hardware", "vm.board_play"],
}
# A guest's test is bounded by its own ctest TIMEOUT; this bounds the whole ctest call around it.
VM_STAGE_LIMIT = 1500

OPERATORS = ("relational", "arithmetic", "constant", "negation", "swap", "removal", "early-return")


def mask(line, in_block_comment):
    """The line with comments and string and character literals blanked (same length), so that
    no operator is found in log text or prose; and whether a block comment is still open."""
    out = []
    i = 0
    n = len(line)
    while i < n:
        if in_block_comment:
            end = line.find("*/", i)
            if end < 0:
                out.append(" " * (n - i))
                return "".join(out), True
            out.append(" " * (end + 2 - i))
            i = end + 2
            in_block_comment = False
            continue
        c = line[i]
        if line.startswith("//", i):
            out.append(" " * (n - i))
            break
        if line.startswith("/*", i):
            in_block_comment = True
            continue
        if c in "\"'":
            # A raw string R"(...)" on one line, or an ordinary literal with escapes.
            if c == '"' and i > 0 and line[i - 1] == "R":
                end = line.find(')"', i)
                end = n if end < 0 else end + 2
            else:
                j = i + 1
                while j < n and line[j] != c:
                    j += 2 if line[j] == "\\" else 1
                end = min(j + 1, n)
            out.append(c + " " * max(0, end - i - 2) + (c if end - i >= 2 else ""))
            i = end
            continue
        out.append(c)
        i += 1
    return "".join(out), in_block_comment


def matching_paren(text, open_index):
    depth = 0
    for k in range(open_index, len(text)):
        if text[k] == "(":
            depth += 1
        elif text[k] == ")":
            depth -= 1
            if depth == 0:
                return k
    return -1


NUMBER = re.compile(r"(?<![\w.])(\d+\.?\d*(?:[eE][+-]?\d+)?)([fFuUlL]*)(?![\w.])")
CALL_STATEMENT = re.compile(r"^(\s+)([A-Za-z_][\w:.>\-\[\]]*(?:\(\))?(?:\.|->)?[A-Za-z_]\w*)\(.*\);$")
TWO_ARGUMENTS = re.compile(r"\b([A-Za-z_]\w*)\(([A-Za-z_][\w.]*), ([A-Za-z_][\w.]*)\)")
DEFINITION = re.compile(r"^(?!\s)(?!(?:namespace|class|struct|enum|union|template|typedef|using|extern|static_assert|#)\b)"
                        r"([^(){};=]*?)\b([A-Za-z_][\w:~]*)\(.*\)( const)?( noexcept)?( override)? \{$")


def sites(path, lines):
    """Every candidate mutant of a file: (line index, operator, new line)."""
    found = []
    in_comment = False
    for index, line in enumerate(lines):
        code, in_comment = mask(line, in_comment)
        stripped = code.strip()
        if not stripped or stripped.startswith("#") or "static_assert" in code:
            continue

        def replace_span(start, end, text):
            return line[:start] + text + line[end:]

        for m in re.finditer(r" (<=|>=|<|>) ", code):
            flipped = {"<": "<=", "<=": "<", ">": ">=", ">=": ">"}[m.group(1)]
            found.append((index, "relational", replace_span(m.start(1), m.end(1), flipped)))
        for m in re.finditer(r" ([-+]) (?!=)", code):
            before, after = code[:m.start()].rstrip(), code[m.end():].lstrip()
            # String concatenation does not build with a minus: not worth a build.
            if (before and before[-1] in "+-=\"") or after.startswith('"'):
                continue
            found.append((index, "arithmetic", replace_span(m.start(1), m.end(1), "-" if m.group(1) == "+" else "+")))
        for m in re.finditer(r" (&&|\|\|) ", code):
            found.append((index, "negation", replace_span(m.start(1), m.end(1), "||" if m.group(1) == "&&" else "&&")))
        for m in re.finditer(r"\b(if|while) \(", code):
            open_index = m.end() - 1
            close = matching_paren(code, open_index)
            if close < 0 or ";" in code[open_index:close]:
                continue
            condition = line[open_index + 1:close]
            found.append((index, "negation", line[:open_index + 1] + "!(" + condition + ")" + line[close:]))
        for m in NUMBER.finditer(code):
            text, suffix = m.group(1), m.group(2)
            # Array extents, bit widths and version numbers are mutated too: a wrong one is a bug.
            value = float(text)
            is_float = "." in text or "e" in text.lower() or "f" in suffix.lower()
            replacements = ["0", "1"] if value not in (0.0, 1.0) else ["1" if value == 0 else "0"]
            if not is_float:
                replacements += [str(int(value) + 1)] + ([str(int(value) - 1)] if value >= 1 else [])
            else:
                replacements = [r + (".0" if "." not in r else "") for r in replacements]
            for r in sorted(set(replacements)):
                if r.rstrip("0").rstrip(".") == text.rstrip("0").rstrip("."):
                    continue
                found.append((index, "constant", replace_span(m.start(1), m.end(1), r)))
        for m in TWO_ARGUMENTS.finditer(code):
            # Keywords are not calls, and swapping the arguments of a symmetric function changes nothing.
            # A macro's arguments (all capitals: an X-macro's type and name) have no type to share, and
            # swapped they only fail to build, each such mutant rebuilding every file that includes it.
            if m.group(2) == m.group(3) or m.group(1) in ("if", "while", "for", "switch", "return", "sizeof", "min", "max",
                                                         "hypot", "swap", "distance", "dot", "equal"):
                continue
            if re.fullmatch(r"[A-Z][A-Z0-9_]*", m.group(1)):
                continue
            found.append((index, "swap", replace_span(m.start(2), m.end(3), m.group(3) + ", " + m.group(2))))
        if CALL_STATEMENT.match(code) and not stripped.startswith(("return", "else", "case", "delete")):
            if code.count("(") == code.count(")"):
                found.append((index, "removal", CALL_STATEMENT.match(code).group(1) + "{}"))
        if path.endswith(".cpp"):
            d = DEFINITION.match(code)
            if d and d.group(1).strip() and "::" not in d.group(2).split("::")[-1]:
                result_type = d.group(1).strip()
                name = d.group(2)
                parts = name.split("::")
                if len(parts) >= 2 and parts[-1] in (parts[-2], "~" + parts[-2]):
                    continue  # a constructor or destructor returns nothing
                if result_type.endswith(("operator", "&&")):
                    continue
                body = "return;" if re.search(r"(^|\s)void$", result_type) else "return {};"
                indent = "  "
                found.append((index, "early-return", line + "\n" + indent + body))
    return found


def collect(folder):
    candidates = []
    for directory, _, names in sorted(os.walk(os.path.join(ROOT, folder))):
        for name in sorted(names):
            if not name.endswith((".cpp", ".h")):
                continue
            path = os.path.relpath(os.path.join(directory, name), ROOT)
            with open(os.path.join(ROOT, path), encoding="utf-8") as f:
                lines = f.read().split("\n")
            for index, op, new in sites(path, lines):
                candidates.append((path, index, op, lines[index], new))
    return candidates


def mutant_id(path, original, new, op):
    digest = hashlib.sha1(f"{path}\0{op}\0{original.strip()}\0{new.strip()}".encode()).hexdigest()[:10]
    return f"{op}-{digest}"


def load_equivalents(folder):
    """FOLDER/mutants.equivalent: blocks of 'file = ', 'line = ', 'mutant = ', 'why = ' keyed by the
    exact line before and after (trimmed), so that an entry survives the code moving."""
    path = os.path.join(ROOT, folder, "mutants.equivalent")
    entries = {}
    if not os.path.exists(path):
        return entries, path
    block = {}
    def close(number):
        if block:
            missing = [k for k in ("file", "line", "mutant", "why") if k not in block]
            if missing:
                sys.exit(f"mutants: {path}:{number}: an entry without {', '.join(missing)}")
            entries[(block["file"], block["line"].strip(), block["mutant"].strip())] = block["why"]
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            line = raw.rstrip("\n")
            if not line.strip() or line.startswith("#"):
                close(number)
                block = {}
                continue
            m = re.match(r"^(file|line|mutant|why) = (.*)$", line)
            if not m:
                sys.exit(f"mutants: {path}:{number}: expected 'file|line|mutant|why = ...', got '{line}'")
            block[m.group(1)] = m.group(2)
        close(number if block else 0)
    return entries, path


def run(command, log, timeout=None, cwd=None, append=False):
    """The command's exit status, or None when it ran past `timeout` (then its whole process group,
    the tests ctest started included, is killed)."""
    with open(log, "a" if append else "w") as out:
        process = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, cwd=cwd, start_new_session=True)
        try:
            return process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
            return None


def ctest_pattern(names):
    """A ctest -R regex that matches exactly these test names (CMake's regex syntax)."""
    escaped = (re.sub(r"([][.*+?^$(){}|\\])", r"\\\1", name) for name in names)
    return "^(" + "|".join(escaped) + ")$"


# CMake's regex compiler refuses an expression past about 32 kB ("Expression too big"), and ctest then
# selects no test and exits 0, as if every test had passed: a mutant whose file hundreds of tests
# reach (lightfield's, through the player's end-to-end tests) was once reported as surviving tests
# that never ran. So the names go in patterns of at most this many characters, one ctest run each,
# and a run that finds no test is an error (--no-tests=error).
PATTERN_LIMIT = 16000


def ctest_patterns(names):
    """ctest -R regexes that together match exactly these test names, each short enough to compile."""
    patterns, chunk = [], []
    for name in names:
        if chunk and len(ctest_pattern(chunk + [name])) > PATTERN_LIMIT:
            patterns.append(ctest_pattern(chunk))
            chunk = []
        chunk.append(name)
    if chunk:
        patterns.append(ctest_pattern(chunk))
    return patterns


def reach(build, src, selector):
    """For each test the selector picks, the source files (headers included) of every program of the
    build tree its command runs, or None where it runs none (then it is always run). Read from
    ninja's own graph and the header dependencies the compiler recorded, so it follows the build."""
    listed = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"] + selector,
                            capture_output=True, check=True, text=True).stdout
    import json
    objects = {}
    current = None
    for line in subprocess.run(["ninja", "-C", build, "-t", "deps"], capture_output=True, check=True,
                               text=True).stdout.splitlines():
        if line and not line.startswith(" "):
            current = objects.setdefault(line.split(": #deps")[0], set())
        elif line.strip() and current is not None:
            path = os.path.normpath(os.path.join(build, line.strip()))
            if path.startswith(src + os.sep):
                current.add(os.path.relpath(path, src))
    programs = {}
    def files_of(program):
        if program not in programs:
            commands = subprocess.run(["ninja", "-C", build, "-t", "commands", os.path.relpath(program, build)],
                                      capture_output=True, text=True).stdout
            programs[program] = set().union(*(objects.get(o, set()) for o in re.findall(r" -o (\S+\.o) ", commands)))
        return programs[program]
    tests = {}
    for test in json.loads(listed)["tests"]:
        words = " ".join(test.get("command") or [])
        found = {p for p in re.findall(re.escape(build) + r"/[^|;=\s'\"]+", words)
                 if os.path.isfile(p) and os.access(p, os.X_OK) and not p.endswith(".so")}
        reached = [files_of(p) for p in found]
        tests[test["name"]] = set().union(*reached) if any(reached) else None
    return tests


def choose(candidates, count, seed):
    """The `count` candidates whose ids hash lowest under `seed` (bottom-k sampling), in that order.
    The same seed and sources give the same mutants; and since a mutant's id comes from its own line,
    an edit changes the choice only where it adds or removes sites: dead code removed to settle an
    equivalent mutant brings one new mutant in, not a new sample of the whole folder."""
    def rank(entry):
        index, (path, _, op, original, new) = entry
        return hashlib.sha1(f"{seed}\0{mutant_id(path, original, new, op)}".encode()).digest(), index

    return [m for _, m in sorted(enumerate(candidates), key=rank)[:count]]


def main():
    parser = argparse.ArgumentParser(prog="tools/mutants --random")
    parser.add_argument("--random", type=int, required=True, metavar="N")
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--folder", required=True)
    parser.add_argument("--tests", help="ctest regex (default: the folder's family)")
    parser.add_argument("--list-only", action="store_true", help="print the mutants, build nothing")
    parser.add_argument("--only", metavar="REGEX", help="of the N, only the mutants whose id matches (a survivor again)")
    parser.add_argument("--no-vm", action="store_true",
                        help="leave out the vm tier's guests (platform, hal), for a machine without QEMU")
    args = parser.parse_args()
    folder = args.folder.strip("/")
    if not os.path.isdir(os.path.join(ROOT, folder)):
        sys.exit(f"mutants: --folder: {folder} is not a folder of the tree")
    tests = args.tests or FAMILIES.get(folder)
    if not tests:
        sys.exit(f"mutants: --folder {folder}: no test family known; give --tests REGEX (known: {', '.join(FAMILIES)})")
    candidates = collect(folder)
    if not candidates:
        sys.exit(f"mutants: no mutable site in {folder}")
    chosen = choose(candidates, args.random, args.seed)
    if args.only:
        chosen = [m for m in chosen if re.search(args.only, mutant_id(m[0], m[3], m[4], m[2]))]
    equivalents, equivalents_path = load_equivalents(folder)
    print(f"mutants: {len(chosen)} of {len(candidates)} candidate mutants in {folder} (seed {args.seed}); tests: {tests}")
    if args.list_only:
        for path, index, op, original, new in chosen:
            print(f"{mutant_id(path, original, new, op)}  {path}:{index + 1}\n  - {original.strip()}\n  + {new.strip()}")
        return 0

    scratch = os.environ.get("MUTANTS_DIR", "/tmp/player-mutants")
    src = os.path.join(scratch, "src")
    build = os.path.join(src, "build", "mutants")
    logs = os.path.join(scratch, "log", "random")
    os.makedirs(logs, exist_ok=True)
    # The scratch tree as tools/mutants makes it: only changed files copied, so builds stay incremental.
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT, capture_output=True,
                            check=True).stdout.decode().split("\0")
    for path in filter(None, listed):
        source, target = os.path.join(ROOT, path), os.path.join(src, path)
        if not os.path.isfile(source):
            continue
        if not os.path.exists(target) or open(source, "rb").read() != open(target, "rb").read():
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copy2(source, target)
    shared = os.path.join(scratch, "shared")
    if not os.path.exists(shared):
        os.symlink(os.path.realpath(os.path.join(ROOT, "..", "shared")), shared)
    if shutil.which("ccache") and os.environ.get("PLAYER_CCACHE", "1") != "0":
        # As tools/test does, and with the build two folders below the sources as the presets have
        # it, so that the release build's cached objects serve the baseline.
        os.environ.setdefault("CCACHE_DIR", os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")),
                                                         "ssao-player", "ccache"))
        os.environ.update(CCACHE_BASEDIR=src, CCACHE_NOHASHDIR="1", CMAKE_C_COMPILER_LAUNCHER="ccache",
                          CMAKE_CXX_COMPILER_LAUNCHER="ccache")
    if run(["cmake", "-S", src, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release"], os.path.join(logs, "configure.txt")):
        sys.exit(f"mutants: configure failed ({logs}/configure.txt)")
    print("== baseline build and the family's tests, unmutated")
    if run(["cmake", "--build", build, "-j2"], os.path.join(logs, "baseline-build.txt")):
        sys.exit(f"mutants: the unmutated tree does not build ({logs}/baseline-build.txt)")
    ctest = ["ctest", "--test-dir", build, "-R", tests, "-E", r"^(vm|fuzz)\.", "--no-tests=error", "-j2"]
    started = time.time()
    if run(ctest + ["--timeout", "900"], os.path.join(logs, "baseline-tests.txt")):
        sys.exit(f"mutants: the family's tests fail without any mutant ({logs}/baseline-tests.txt)")
    baseline = time.time() - started
    vm_tests = [] if args.no_vm or args.tests else VM_FAMILIES.get(folder, [])
    if vm_tests:
        print(f"== the vm tier's tests, unmutated: {', '.join(vm_tests)}")
        vm_log = os.path.join(logs, "baseline-vm.txt")
        code = run(["ctest", "--test-dir", build, "-R", ctest_pattern(vm_tests), "--timeout", "900"], vm_log,
                   timeout=VM_STAGE_LIMIT * len(vm_tests))
        skipped = re.findall(r"^\s*\d+/\d+ Test\s+#\d+: (\S+) \.+\*+Skipped", open(vm_log).read(), re.M)
        if code != 0 or skipped:
            sys.exit(f"mutants: the vm tier does not pass unmutated ({vm_log}{': skipped ' + ', '.join(skipped) if skipped else ''});"
                     " --no-vm leaves it out")
    limit = int(baseline * 3 + 120)
    # Only the tests whose programs hold the mutated file can notice it: a mutant in a file no test
    # program links (a module loaded at run time) runs the whole family.
    reached_by = reach(build, src, ["-R", tests, "-E", r"^(vm|fuzz)\."])
    vm_reached_by = reach(build, src, ["-R", ctest_pattern(vm_tests)]) if vm_tests else {}

    results = []
    for number, (path, index, op, original, new) in enumerate(chosen, 1):
        ident = mutant_id(path, original, new, op)
        target = os.path.join(src, path)
        with open(target, encoding="utf-8") as f:
            text = f.read()
        lines = text.split("\n")
        if lines[index] != original:
            sys.exit(f"mutants: {path}:{index + 1} differs in the scratch tree")
        lines[index] = new
        start = time.time()
        try:
            with open(target, "w", encoding="utf-8") as f:
                f.write("\n".join(lines))
            if run(["cmake", "--build", build, "-j2"], os.path.join(logs, f"{ident}-build.txt")):
                result, by = "did not build", ""
            else:
                chosen_tests = [name for name, files in reached_by.items() if files is None or path in files]
                if not any(path in files for files in reached_by.values() if files):
                    chosen_tests = list(reached_by)
                # The component's own test programs first, the end-to-end tests of the player only
                # when those pass: most mutants die in the first seconds.
                stages = [[t for t in chosen_tests if not END_TO_END.match(t)], [t for t in chosen_tests if END_TO_END.match(t)]]
                code = 0
                with open(os.path.join(logs, f"{ident}-tests.txt"), "w"):
                    pass
                for pattern in (p for names in filter(None, stages) for p in ctest_patterns(names)):
                    code = run(["ctest", "--test-dir", build, "-R", pattern, "--no-tests=error", "-j2", "--stop-on-failure",
                                "--timeout", str(limit)], os.path.join(logs, f"{ident}-tests.txt"), timeout=limit * 2,
                               append=True)
                    if code != 0:
                        break
                if code == 0:
                    for name in vm_tests:
                        if vm_reached_by.get(name) is not None and path not in vm_reached_by[name]:
                            continue
                        chosen_tests.append(name)
                        code = run(["ctest", "--test-dir", build, "-R", ctest_pattern([name]), "--no-tests=error"],
                                   os.path.join(logs, f"{ident}-tests.txt"), timeout=VM_STAGE_LIMIT, append=True)
                        if code != 0:
                            break
                if code is None:
                    result, by = "timed out", ""
                elif code == 0:
                    why = equivalents.get((path, original.strip(), new.strip()))
                    if why and why.startswith("killed by "):
                        result, by = "killed", why  # by a tier the release build cannot be (ASan)
                    else:
                        result, by = ("equivalent", why) if why else ("SURVIVED", f"{len(chosen_tests)} tests ran")
                else:
                    failed = re.findall(r"^\s+\d+ - (\S+)", open(os.path.join(logs, f"{ident}-tests.txt")).read(), re.M)
                    timeouts = "Timeout" in open(os.path.join(logs, f"{ident}-tests.txt")).read()
                    result, by = ("timed out" if timeouts and not failed else "killed"), " ".join(failed[:2])
        finally:
            # Written back with a newer time than the mutant's objects, so the next build recompiles it.
            with open(target, "w", encoding="utf-8") as f:
                f.write(text)
        results.append((ident, path, index, op, original, new, result, by))
        print(f"[{number}/{len(chosen)}] {result:<13} {ident} {path}:{index + 1} {int(time.time() - start)}s {by}", flush=True)
    run(["cmake", "--build", build, "-j2"], os.path.join(logs, "restore-build.txt"))

    counts = {k: sum(1 for r in results if r[6] == k) for k in ("killed", "timed out", "SURVIVED", "equivalent", "did not build")}
    built = len(results) - counts["did not build"]
    detected = counts["killed"] + counts["timed out"]
    rate = 100.0 * detected / built if built else 0.0
    part = "-only" if args.only else ""
    report = os.path.join(ROOT, "out", "mutants", f"random-{folder.replace('/', '-')}-seed{args.seed}{part}.md")
    os.makedirs(os.path.dirname(report), exist_ok=True)
    with open(report, "w") as out:
        out.write(f"# Random mutants: {folder}, seed {args.seed}, {len(results)} mutants\n\n")
        out.write(f"Tests: `{tests}`. Killed {counts['killed']}, timed out {counts['timed out']}, survived "
                  f"{counts['SURVIVED']}, equivalent {counts['equivalent']}, did not build {counts['did not build']}; "
                  f"{rate:.1f}% of the {built} that built were detected.\n\n")
        out.write("| mutant | where | operator | before | after | result | killed by / why equivalent |\n|---|---|---|---|---|---|---|\n")
        for ident, path, index, op, original, new, result, by in results:
            cell = lambda s: "`" + s.strip().replace("|", "\\|").replace("\n", " ") + "`"
            out.write(f"| {ident} | {path}:{index + 1} | {op} | {cell(original)} | {cell(new)} | {result} | {by} |\n")
    print(f"mutants: {len(results)} run: {counts['killed']} killed, {counts['timed out']} timed out, {counts['SURVIVED']} survived, "
          f"{counts['equivalent']} named equivalent ({os.path.relpath(equivalents_path, ROOT)}), {counts['did not build']} did not "
          f"build; {rate:.1f}% of those that built detected; report {os.path.relpath(report, ROOT)}")
    return 0 if counts["SURVIVED"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
