# Shared fixtures of the Python tests: the CLI (SHADELAB_EXE, set by CTest) to compare against, and data paths.
import json
import os
import subprocess
from pathlib import Path

import pytest


def _exe():
    exe = os.environ.get("SHADELAB_EXE")
    if not exe:
        pytest.fail("SHADELAB_EXE is not set: run these tests through CTest (ctest -R python)")
    return exe


class Cli:
    """Runs the shadelab command-line tool and returns (exit code, stdout, stderr)."""

    def __init__(self, exe):
        self.exe = exe

    def __call__(self, *args, cwd=None):
        p = subprocess.run([self.exe, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=300)
        return p.returncode, p.stdout, p.stderr

    def json(self, *args, cwd=None):
        rc, out, err = self(*args, cwd=cwd)
        assert rc == 0, f"shadelab {' '.join(map(str, args))} failed ({rc}): {err}"
        return json.loads(out)

    def error(self, *args, cwd=None):
        """The one line the CLI prints for bad input, without its 'shadelab: ' prefix (exit code 2)."""
        rc, out, err = self(*args, cwd=cwd)
        assert rc == 2, f"expected exit code 2, got {rc}: {out} {err}"
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("shadelab: "), err
        return lines[0][len("shadelab: "):]


@pytest.fixture(scope="session")
def cli():
    return Cli(_exe())


@pytest.fixture(scope="session")
def measured_file(cli, tmp_path_factory):
    """A MERL 100 file for the `measured` model (35 MB, about 1 s): `shadelab measure` of a coloured glossy ggx."""
    path = tmp_path_factory.mktemp("measured") / "ggx.binary"
    rc, _, err = cli("measure", "ggx", "--param", "roughness=0.4", "--param", "kd=0.3", "--param", "f0=0.9,0.6,0.3",
                     "--out", path)
    assert rc == 0, err
    return path


@pytest.fixture(scope="session")
def scenes_dir():
    return Path(os.environ.get("SHADELAB_SCENES_DIR", Path(__file__).resolve().parents[2] / "scenes"))


@pytest.fixture(scope="session")
def blender_world():
    """One of Debian blender-data's CC0 studio-light worlds (scripts/setup.sh installs the package)."""
    folder = Path(os.environ.get("SHADELAB_BLENDER_WORLDS", "/usr/share/blender/datafiles/studiolights/world"))
    worlds = sorted(folder.glob("*.exr"))
    assert worlds, f"no EXR worlds in {folder}: install blender-data (scripts/setup.sh)"
    return worlds[0]
