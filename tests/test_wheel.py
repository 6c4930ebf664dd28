"""The package as a user installs it: a wheel, in a fresh virtual environment, away from the repository.

An editable install reads models/ and diagrams/ from the checkout; a wheel must carry them. The test
builds the wheel with this environment's setuptools, installs it (without dependencies) into a new
venv that borrows this environment's third-party packages (Drake, numpy, ...) through a .pth line, and
runs a real command from an empty folder: the hand, the arm and the scenario must all load from inside
the installed package.
"""

import json
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig
import venv

REPO = pathlib.Path(__file__).resolve().parents[1]


# No PYTHONPATH: a checkout on the path would pass for an installed drake-grasp.
CLEAN_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


def _run(command, **kw):
    result = subprocess.run(command, capture_output=True, text=True, env=CLEAN_ENV, **kw)
    assert result.returncode == 0, f"{command} failed:\n{result.stdout[-2000:]}\n{result.stderr[-2000:]}"
    return result


def test_wheel_installs_and_runs_a_demo_outside_the_repository(tmp_path):
    # Built from a copy of the sources, so the checkout gets no build/ or egg-info of the test's.
    source = tmp_path / "source"
    shutil.copytree(REPO, source, symlinks=True,
                    ignore=shutil.ignore_patterns(".git", ".venv", "out", "build", "*.egg-info", "__pycache__"))
    wheels = tmp_path / "wheels"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(wheels),
          str(source)], cwd=tmp_path)
    (wheel,) = wheels.glob("drake_grasp-*.whl")

    env_dir = tmp_path / "venv"
    venv.EnvBuilder(with_pip=False).create(env_dir)
    python = env_dir / "bin" / "python"
    purelib = pathlib.Path(_run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"])
                           .stdout.strip())
    _run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q", "--no-deps", str(wheel)],
         cwd=tmp_path)
    # Then the dependencies, from this environment (a plain path line: its own .pth files, such as an
    # editable install's finder, are not processed, so the checkout stays invisible). After the
    # install: pip would otherwise take this environment's drake-grasp for an installed one.
    (purelib / "borrowed_dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")

    work = tmp_path / "elsewhere"
    work.mkdir()
    where = _run([str(python), "-c", "import drake_grasp.paths as p; print(p.MODELS_DIR.resolve())"],
                 cwd=work).stdout.strip()
    assert pathlib.Path(where).is_relative_to(purelib), where  # the installed copy, not the checkout
    assert not pathlib.Path(where).is_relative_to(REPO)
    out = _run([str(env_dir / "bin" / "drake-grasp"), "demo", "--object", "soccer_ball", "--json"],
               cwd=work, timeout=600)
    record = json.loads(out.stdout)
    assert record["object_name"] == "soccer_ball"
    assert record["held"] is True  # a real simulation ran: the hand picked the ball up
