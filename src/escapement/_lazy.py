"""Re-exports imported on first use (PEP 562), for the package and its layers' ``__init__``: ``import escapement``
costs about 40 ms of CPU time this way, 190 ms with every layer imported (NumPy, the solvers, SciPy)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from importlib import import_module
from typing import Any


def lazy_exports(package: str, exports: Mapping[str, str], namespace: dict[str, Any]
                 ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for ``package``, whose public names ``exports`` maps to the submodule that
    defines each, imported on first use and kept in ``namespace``; ``dir`` lists them, ``__all__`` and the dunders."""

    def __getattr__(name: str) -> Any:
        if name not in exports:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(import_module(f".{exports[name]}", package), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        dunders = (name for name in namespace if name.startswith("__") and name.endswith("__"))
        return sorted({*exports, *namespace.get("__all__", ()), *dunders})

    return __getattr__, __dir__
