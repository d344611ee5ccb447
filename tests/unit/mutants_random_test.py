#!/usr/bin/env python3
"""tools/mutants --random: what it may mutate and what it must leave alone, and that a seed picks
the same mutants every time. Run by ctest as unit.mutants_random (tools/mutants_random.py's own
argument is the tree's root)."""
import os
import re
import subprocess
import sys
import unittest

ROOT = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import mutants_random  # noqa: E402


def mutants(lines, path="x.cpp"):
    return [(index, op, new) for index, op, new in mutants_random.sites(path, lines)]


class Operators(unittest.TestCase):
    def test_each_operator_has_its_mutant(self):
        found = mutants([
            "int f(int a, int b) {",
            "  if (a < b && b > 2) g(a, b);",
            "  return a + b;",
            "}",
        ])
        new_lines = {(op, new) for _, op, new in found}
        self.assertIn(("relational", "  if (a <= b && b > 2) g(a, b);"), new_lines)
        self.assertIn(("relational", "  if (a < b && b >= 2) g(a, b);"), new_lines)
        self.assertIn(("negation", "  if (a < b || b > 2) g(a, b);"), new_lines)
        self.assertIn(("negation", "  if (!(a < b && b > 2)) g(a, b);"), new_lines)
        self.assertIn(("constant", "  if (a < b && b > 0) g(a, b);"), new_lines)
        self.assertIn(("constant", "  if (a < b && b > 3) g(a, b);"), new_lines)
        self.assertIn(("swap", "  if (a < b && b > 2) g(b, a);"), new_lines)
        self.assertIn(("arithmetic", "  return a - b;"), new_lines)
        self.assertIn(("early-return", "int f(int a, int b) {\n  return {};"), new_lines)

    def test_a_call_statement_is_removed_and_a_void_function_returns_early(self):
        new_lines = {(op, new) for _, op, new in mutants(["void Loop::stop() {", "  timer_.cancel(now);", "}"])}
        self.assertIn(("removal", "  {}"), new_lines)
        self.assertIn(("early-return", "void Loop::stop() {\n  return;"), new_lines)

    def test_comments_strings_and_preprocessor_lines_are_left_alone(self):
        found = mutants([
            '  log("a < b && c + 1 > 2");  // x < y || 3 - 1',
            "  /* if (a < b) return 1 + 2;",
            "     still a comment: a > 0 */",
            "#define LIMIT (1 + 2)",
            "  const char c = '<';",
        ])
        for index, op, new in found:
            self.assertEqual(op, "removal", f"line {index + 1}: {op} -> {new}")

    def test_symmetric_calls_and_constructors_are_not_mutated(self):
        found = mutants(["Loop::Loop(int a) {", "  x = std::max(a, b);", "}"])
        self.assertFalse([m for m in found if m[1] in ("swap", "early-return")], found)

    def test_a_macros_arguments_are_not_swapped(self):
        found = mutants(["  X(PFNGLREADPIXELSPROC, ReadPixels) X(PFNGLPIXELSTOREIPROC, PixelStorei)  \\"])
        self.assertFalse([m for m in found if m[1] == "swap"], found)
        self.assertTrue([m for m in mutants(["  x = f(a, b);"]) if m[1] == "swap"])


class Selection(unittest.TestCase):
    def listing(self, seed):
        return subprocess.run([sys.executable, os.path.join(ROOT, "tools", "mutants_random.py"), "--random", "20", "--seed",
                               str(seed), "--folder", "player/playback", "--list-only"], capture_output=True, text=True,
                              check=True).stdout

    def test_the_same_seed_gives_the_same_mutants_and_another_seed_others(self):
        first = self.listing(7)
        self.assertEqual(first, self.listing(7))
        self.assertNotEqual(first, self.listing(8))
        self.assertEqual(first.count("\n  + "), 20)

    def test_an_edit_changes_the_choice_only_where_it_adds_or_removes_sites(self):
        candidates = [(f"f{i % 7}.cpp", i, "constant", f"int v{i} = 0;", f"int v{i} = 1;") for i in range(200)]
        chosen = mutants_random.choose(candidates, 20, 3)
        self.assertEqual(len(chosen), 20)
        self.assertEqual(chosen, mutants_random.choose(list(reversed(candidates)), 20, 3))
        self.assertNotEqual(set(chosen), set(mutants_random.choose(candidates, 20, 4)))
        # A chosen site removed: the other 19 stay and one comes in; a site not chosen removed: no change.
        without_chosen = [c for c in candidates if c != chosen[5]]
        again = mutants_random.choose(without_chosen, 20, 3)
        self.assertEqual(len(set(again) & set(chosen)), 19)
        not_chosen = next(c for c in candidates if c not in chosen)
        self.assertEqual(mutants_random.choose([c for c in candidates if c != not_chosen], 20, 3), chosen)

    def test_a_test_name_becomes_an_exact_ctest_pattern(self):
        self.assertEqual(mutants_random.ctest_pattern(["gl.Platforms/A.b", "x(y)"]), r"^(gl\.Platforms/A\.b|x\(y\))$")

    def test_many_test_names_are_split_into_patterns_cmake_can_compile(self):
        # CMake's regex compiler refuses an expression past about 32 kB, and ctest then runs nothing
        # and passes: 2000 names of 40 characters must not reach it as one pattern.
        names = [f"unit.SomeSuite{i}.SomeLongishTestName{i}" for i in range(2000)]
        patterns = mutants_random.ctest_patterns(names)
        self.assertGreater(len(patterns), 1)
        self.assertTrue(all(len(p) <= mutants_random.PATTERN_LIMIT for p in patterns))
        matched = [n for n in names + ["unit.SomeSuite1.SomeLongishTestName12"] if any(re.search(p, n) for p in patterns)]
        self.assertEqual(matched, names)
        self.assertEqual(mutants_random.ctest_patterns(["a.b"]), [mutants_random.ctest_pattern(["a.b"])])


class Families(unittest.TestCase):
    def test_every_family_names_a_folder_of_code_and_every_vm_test_exists(self):
        for folder in list(mutants_random.FAMILIES) + list(mutants_random.VM_FAMILIES):
            self.assertTrue(os.path.isdir(os.path.join(ROOT, folder)), folder)
        with open(os.path.join(ROOT, "tests", "vm", "CMakeLists.txt")) as f:
            defined = {"vm." + name for name in re.findall(r"player_vm_test\(NAME (\w+)", f.read())}
        for folder, tests in mutants_random.VM_FAMILIES.items():
            self.assertTrue(tests, folder)
            self.assertLessEqual(set(tests), defined, folder)


if __name__ == "__main__":
    unittest.main()
