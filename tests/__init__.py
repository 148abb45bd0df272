# SPDX-License-Identifier: BSD-3-Clause
"""gencoord's tests. They import the package of this checkout (python/gencoord), not an
installed one."""
import os
import sys

_REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_PACKAGE_PARENT = os.path.join(_REPOSITORY, "python")
if _PACKAGE_PARENT not in sys.path:
    sys.path.insert(0, _PACKAGE_PARENT)
