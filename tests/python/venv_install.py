"""CTest python.install: installs the package the way a user does and runs it from outside the
clone (docs/python.md, "Installing").

    venv_install.py <source dir> <build dir> <work dir>

1. a fresh virtual environment <work dir>/venv (`python3 -m venv --system-site-packages`: numpy,
   pytest, pip, setuptools and wheel come from the system, as on a Debian machine without
   network);
2. `pip install --no-build-isolation --no-index .` of the source tree, with
   STICKSLIP_CMAKE_BUILD_DIR=<build dir>: setup.py packages the module this build tree has
   built (its target is up to date: nothing is compiled again);
3. from <work dir> (outside the clone, no PYTHONPATH): the quick start examples/python/quickstart.py,
   then the Python tests tests/python against the installed package (conftest.py checks that
   `stickslip` is imported from the environment's site-packages, STICKSLIP_TEST_INSTALLED=1).

Prints each step's time; exits non-zero when a step fails."""
import os
import shutil
import subprocess
import sys
import time


def step(name, args, **kwargs):
    t0 = time.monotonic()
    print("python.install: " + name + ": " + " ".join(args), flush=True)
    subprocess.run(args, check=True, **kwargs)
    print("python.install: %s: %.1f s" % (name, time.monotonic() - t0), flush=True)


def main():
    source, build, work = (os.path.abspath(a) for a in sys.argv[1:4])
    venv = os.path.join(work, "venv")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "PIP_USER")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    env["PYTHONDONTWRITEBYTECODE"] = "1"  # no __pycache__ in the sources
    # Without its own pip (ensurepip takes most of the venv's time): the system's pip, seen
    # through --system-site-packages, installs into the environment it runs in.
    step("venv", [sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", venv], env=env)
    python = os.path.join(venv, "bin", "python")
    if subprocess.run([python, "-m", "pip", "--version"], env=env, stdout=subprocess.DEVNULL).returncode != 0:
        step("ensurepip", [python, "-m", "ensurepip"], env=env)
    install_env = dict(env, STICKSLIP_CMAKE_BUILD_DIR=build)
    step("pip install", [python, "-m", "pip", "install", "--quiet", "--no-build-isolation", "--no-index", source],
         env=install_env, cwd=work)
    run_env = dict(env, STICKSLIP_TEST_INSTALLED="1")
    step("quickstart", [python, os.path.join(source, "examples", "python", "quickstart.py")], env=run_env, cwd=work)
    step("pytest", [python, "-m", "pytest", "-q", "-p", "no:cacheprovider", os.path.join(source, "tests", "python")],
         env=run_env, cwd=work)


if __name__ == "__main__":
    main()
