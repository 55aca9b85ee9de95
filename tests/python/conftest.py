"""pytest setup: the example's blade scene (examples/python/blade_scene.py) on sys.path, and the
module `stickslip` from where it was put: the build tree (PYTHONPATH=<build>/python) or, with
STICKSLIP_TEST_INSTALLED=1 (CTest python.install), the installed package, which must then come
from the running environment's site-packages and not from a build tree."""
import os
import sys
import sysconfig

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python"))

if os.environ.get("STICKSLIP_TEST_INSTALLED") == "1":
    import stickslip

    site = os.path.realpath(sysconfig.get_paths()["platlib"])
    where = os.path.realpath(stickslip.__file__)
    if os.path.dirname(where) != site:
        raise RuntimeError("STICKSLIP_TEST_INSTALLED=1: stickslip was imported from %s, not from the "
                           "environment's site-packages %s" % (where, site))
