"""Every public function, method and property of the package has a docstring; every public class,
function and method has one with an example (a `>>>` line)."""
import inspect

import mocapdb


def public_names():
    for name in mocapdb.__all__ if hasattr(mocapdb, "__all__") else dir(mocapdb):
        if name.startswith("_"):
            continue
        obj = getattr(mocapdb, name)
        if not inspect.ismodule(obj):
            yield name, obj


def public_members():
    for name, obj in public_names():
        yield name, obj
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for member, value in vars(obj).items():
                if member.startswith("_") and member not in ("__init__",):
                    continue
                yield f"{name}.{member}", value


def test_every_public_name_is_documented():
    missing = []
    for name, obj in public_members():
        doc = getattr(obj, "__doc__", None)
        # pybind11 writes the signature as the first docstring line; a description must follow it.
        lines = [l for l in (doc or "").strip().splitlines() if l.strip()]
        described = [l for l in lines if not l.lstrip().startswith(name.split(".")[-1] + "(") and "->" not in l]
        if not described:
            missing.append(name)
    assert not missing, f"without a docstring: {missing}"


def test_every_public_class_function_and_method_has_an_example():
    missing = []
    for name, obj in public_names():
        if not (inspect.isclass(obj) or callable(obj)):
            continue
        if ">>> " not in (obj.__doc__ or ""):
            missing.append(name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for member, value in vars(obj).items():
                if member.startswith("_") or isinstance(value, property) or not callable(getattr(obj, member)):
                    continue
                if ">>> " not in (getattr(obj, member).__doc__ or ""):
                    missing.append(f"{name}.{member}")
    assert not missing, f"without an example: {missing}"
