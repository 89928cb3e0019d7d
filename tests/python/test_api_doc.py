# SPDX-License-Identifier: GPL-3.0-or-later
"""docs/python-api.md is what scripts/python-api-doc.py generates from the module."""
import subprocess
import sys

from conftest import SOURCE


def test_the_python_reference_page_is_generated_from_the_module():
    done = subprocess.run([sys.executable, str(SOURCE / "scripts" / "python-api-doc.py"),
                           "--check"], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr
