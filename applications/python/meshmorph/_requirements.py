# SPDX-License-Identifier: GPL-3.0-or-later
"""What meshmorph needs to load (numpy, a C++ extension built for this interpreter), and the
message when it is missing: which interpreter this is, which one the module was built for,
and the command that installs it here. Imports nothing that may be missing."""
import os
import platform
import sys
import sysconfig

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def _build_info():
    try:
        from . import _build_info as info
    except ImportError:
        return None
    return info


def _built_for():
    info = _build_info()
    if info is None:
        return ("no interpreter: this is meshmorph's source directory, not a built or "
                "installed copy (it has no _build_info.py)")
    return f"{info.PYTHON} (Python {info.PYTHON_VERSION}, extension {info.EXTENSION})"


def _this_interpreter():
    suffix = sysconfig.get_config_var("EXT_SUFFIX") or ".so"
    return f"{sys.executable} (Python {platform.python_version()}, extension _core{suffix})"


def _install_command():
    info = _build_info()
    source = info.SOURCE_DIR if info else "<meshMorph's source directory>"
    return f"{sys.executable} -m pip install --no-build-isolation --no-index {source}"


def missing_numpy():
    """None when numpy imports, else the message naming this interpreter and the remedy."""
    try:
        import numpy  # noqa: F401
    except ImportError as error:
        return (f"meshmorph needs numpy, and this interpreter cannot import it ({error}).\n"
                f"  this interpreter: {_this_interpreter()}\n"
                f"  meshmorph in {PACKAGE_DIR} was built for: {_built_for()}\n"
                "Run the interpreter it was built for, or install numpy for this one "
                f"({sys.executable} -m pip install numpy; Debian's python3: apt-get install "
                "python3-numpy) and meshmorph with it: " + _install_command())
    return None


def core_not_loading(error):
    """The message when the C++ extension meshmorph._core does not load (error)."""
    return (f"meshmorph's C++ extension does not load in this interpreter ({error}).\n"
            f"  this interpreter: {_this_interpreter()}\n"
            f"  meshmorph in {PACKAGE_DIR} was built for: {_built_for()}\n"
            "Run the interpreter it was built for, or install meshmorph for this one: "
            + _install_command())
