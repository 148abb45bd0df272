# SPDX-License-Identifier: BSD-3-Clause
"""three.js for the viewer page: one pinned release from the npm registry, checked against the
registry's integrity hash and kept in the per-user cache, so that it is fetched once per
machine and every page carries it inline (a page never fetches anything).

Without the network, put the release's tarball (three-<VERSION>.tgz, as `npm pack
three@<VERSION>` writes it) in the cache folder by hand; GENCOORD_NPM_REGISTRY names another
registry (a mirror).
"""

from __future__ import annotations

import base64
import hashlib
import io
import os
import tarfile
import tempfile
import urllib.error
import urllib.request

from gencoord.tool.errors import ToolError
from gencoord.tool.layout import cache_dir

VERSION = "0.170.0"
# the registry's "integrity" of three-0.170.0.tgz (npm view three@0.170.0 dist.integrity)
INTEGRITY = ("sha512-FQK+LEpYc0fBD+J8g6oSEyyNzjp+Q7Ks1C568WWaoMRLW+TkNNWmenWeGgJjV105Gd+p/2ql1Zc"
             "jYvNiPZBhuQ==")
REGISTRY = "https://registry.npmjs.org"
# the package's files a page needs: the library and the camera's orbit control
FILES = {"three": "package/build/three.module.min.js",
         "orbit_controls": "package/examples/jsm/controls/OrbitControls.js",
         "license": "package/LICENSE"}
TIMEOUT_S = 60


def _tarball_path() -> str:
    return os.path.join(cache_dir(), "three", f"three-{VERSION}.tgz")


def _verified(data: bytes, origin: str) -> bytes:
    algorithm, _, expected = INTEGRITY.partition("-")
    actual = base64.b64encode(hashlib.new(algorithm, data).digest()).decode()
    if actual != expected:
        raise ToolError(f"{origin} is not three.js {VERSION} as the npm registry publishes it "
                        f"(its {algorithm} differs); delete it to fetch it again")
    return data


def _download() -> bytes:
    registry = os.environ.get("GENCOORD_NPM_REGISTRY", REGISTRY).rstrip("/")
    url = f"{registry}/three/-/three-{VERSION}.tgz"
    try:
        with urllib.request.urlopen(url, timeout=TIMEOUT_S) as response:
            return _verified(response.read(), url)
    except (urllib.error.URLError, OSError) as error:
        raise ToolError(f"cannot fetch three.js {VERSION} from {url} ({error}); connect to the "
                        f"network once, or put three-{VERSION}.tgz (npm pack three@{VERSION}) "
                        f"into {os.path.dirname(_tarball_path())}") from None


def tarball() -> bytes:
    """The release's tarball: from the cache, else downloaded into it (atomically)."""
    path = _tarball_path()
    if os.path.isfile(path):
        with open(path, "rb") as handle:
            return _verified(handle.read(), path)
    data = _download()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    descriptor, partial = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".partial")
    with os.fdopen(descriptor, "wb") as handle:
        handle.write(data)
    os.replace(partial, path)
    return data


def sources() -> dict[str, str]:
    """The text of each of FILES, by key."""
    with tarfile.open(fileobj=io.BytesIO(tarball()), mode="r:gz") as archive:
        texts = {}
        for key, member in FILES.items():
            handle = archive.extractfile(member)
            if handle is None:
                raise ToolError(f"three.js {VERSION}'s tarball lacks {member}")
            texts[key] = handle.read().decode("utf-8")
    return texts
