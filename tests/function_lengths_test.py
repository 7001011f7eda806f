#!/usr/bin/python3
"""Tests of tools/function_lengths.py on small C++ snippets, run by ctest (function_lengths_checker)."""
import contextlib
import io
import os
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import function_lengths  # noqa: E402

SOURCE = r'''
#include <string>
namespace a {
struct S {
    S(int x) : x_{x}, y_(x) {
        const char* s = "}{";
    }
    int f() const { return '}'; }
    int x_{0}, y_;
};
enum class E { A, B };
// void commented() {
int S_g(int a) {
    auto l = [](int b) { return b; };
    if (a) { a = 1; }
    const char* r = R"(} } {)";
    return l(a);
}
int S::long_one() noexcept
{
    int x = 1'000;
    LINES
    return x;
}
}  // namespace a
'''


def write(tmp, lines):
    path = os.path.join(tmp, "t.cpp")
    with open(path, "w") as f:
        f.write(SOURCE.replace("LINES", "\n".join("x += 1;" for _ in range(lines))))
    return path


class FunctionLengths(unittest.TestCase):
    def test_functions_and_lengths(self):
        with tempfile.TemporaryDirectory() as tmp:
            found = {name: (line, length) for name, line, length in function_lengths.scan(write(tmp, 10))}
        self.assertEqual(set(found), {"S", "f", "S_g", "S::long_one"})
        self.assertEqual(found["S"], (5, 3))
        self.assertEqual(found["f"], (8, 1))
        self.assertEqual(found["S_g"], (13, 6))
        self.assertEqual(found["S::long_one"], (19, 15))

    def run_main(self, args):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            rc = function_lengths.main(args)
        return rc, out.getvalue()

    def test_max_and_ignore(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = write(tmp, 10)
            self.assertEqual(self.run_main(["--max", "15", path])[0], 0)
            rc, out = self.run_main(["--max", "14", path])
            self.assertEqual(rc, 1)
            self.assertIn("S::long_one", out)
            self.assertEqual(self.run_main(["--max", "14", "--ignore", "S::long_one", path])[0], 0)
            self.assertEqual(self.run_main(["--max", "14", "--ignore", "long_one", path])[0], 0)


if __name__ == "__main__":
    unittest.main()
