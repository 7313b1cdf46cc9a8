"""The hand-written stub (octomotion/__init__.pyi) names exactly what the module offers."""

import ast
import inspect
import os
import unittest

import octomotion


def public(names):
    return {n for n in names if not n.startswith("_")}


class StubTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        path = os.path.join(os.path.dirname(octomotion.__file__), "__init__.pyi")
        with open(path) as f:
            cls.tree = ast.parse(f.read())
        cls.top = {}
        for node in cls.tree.body:
            if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
                cls.top[node.name] = node

    def test_module_names(self):
        module = {n for n in public(dir(octomotion))
                  if not inspect.ismodule(getattr(octomotion, n))}
        self.assertEqual(module, public(self.top))
        self.assertEqual(set(octomotion.__all__), module)

    def test_class_members(self):
        for name in ("Scene", "Reason"):
            stub = public(n.name for n in self.top[name].body if isinstance(n, ast.FunctionDef))
            self.assertEqual(public(dir(getattr(octomotion, name))), stub, name)

    def test_function_parameters(self):
        for name in ("load_scene", "trade_study", "bench_set"):
            stub = self.top[name].args
            real = inspect.signature(getattr(octomotion, name)).parameters
            stub_names = [a.arg for a in stub.args + stub.kwonlyargs]
            for p in real.values():
                if p.kind != p.VAR_KEYWORD:
                    self.assertIn(p.name, stub_names, name)


if __name__ == "__main__":
    unittest.main()
