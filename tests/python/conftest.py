"""pytest setup: the module from the build tree (PYTHONPATH, set by CTest) and the example's
blade scene (examples/python/blade_scene.py)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python"))
