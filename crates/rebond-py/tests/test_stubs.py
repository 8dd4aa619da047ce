"""The typed stubs describe the module as built: same classes, same methods and properties."""

import ast
import inspect
import os

import rebond
from rebond import _rebond

STUBS = os.path.join(os.path.dirname(rebond.__file__), "_rebond.pyi")


def stub_classes():
    tree = ast.parse(open(STUBS, encoding="utf-8").read())
    classes = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names = {
                item.name
                for item in node.body
                if isinstance(item, ast.FunctionDef)
                and (not item.name.startswith("_") or item.name == "__len__")
            }
            classes[node.name] = names
    return classes


def test_the_package_ships_its_stubs_and_marker():
    assert os.path.exists(STUBS)
    assert os.path.exists(os.path.join(os.path.dirname(rebond.__file__), "py.typed"))


def test_every_class_and_method_of_the_module_is_in_the_stubs():
    stubs = stub_classes()
    runtime = {
        name: value for name, value in vars(_rebond).items()
        if inspect.isclass(value) and not name.startswith("_")
    }
    assert set(stubs) == set(runtime)
    for name, cls in runtime.items():
        if issubclass(cls, Exception):
            continue
        members = {
            member for member in vars(cls)
            if not member.startswith("_") or member == "__len__"
        }
        assert stubs[name] == members, name


def test_the_package_exports_what_the_module_has():
    assert set(rebond.__all__) >= {"World", "Batch", "RayHit", "SceneError", "StepError"}
    assert issubclass(rebond.SceneError, ValueError)
    assert issubclass(rebond.StepError, RuntimeError)

