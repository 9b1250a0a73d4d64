"""Shared fixtures: the pfgen program the module is compared with, and the example models."""
import glob
import os
import subprocess

import pytest

# Simulation.plot's figures are drawn off screen, as on a machine without a display.
os.environ.setdefault("MPLBACKEND", "Agg")

SOURCE_DIR = os.environ.get("PFGEN_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
PFGEN = os.environ.get("PFGEN_EXECUTABLE", "pfgen")


def example_models():
    """Every example model file, relative to the source directory (as the commands are given it)."""
    paths = sorted(glob.glob(os.path.join(SOURCE_DIR, "examples", "**", "*.yaml"), recursive=True))
    return [os.path.relpath(p, SOURCE_DIR) for p in paths]


class Command:
    """The pfgen program, run in the source directory."""

    def run(self, *args, check=True):
        done = subprocess.run([PFGEN, *args], cwd=SOURCE_DIR, capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"pfgen {' '.join(args)} failed ({done.returncode}): {done.stderr}")
        return done

    def error_line(self, *args):
        """The one line a refused command prints on stderr, without "pfgen: "."""
        done = self.run(*args, check=False)
        assert done.returncode != 0, f"pfgen {' '.join(args)} did not fail"
        lines = [line for line in done.stderr.splitlines() if not line.startswith("pfgen: note:")]
        assert len(lines) == 1 and lines[0].startswith("pfgen: "), done.stderr
        return lines[0][len("pfgen: "):]


@pytest.fixture(scope="session")
def pfgen_command():
    return Command()


@pytest.fixture(scope="session", autouse=True)
def in_source_dir():
    """Models are loaded by the paths the commands are given, relative to the source directory."""
    previous = os.getcwd()
    os.chdir(SOURCE_DIR)
    yield
    os.chdir(previous)


@pytest.fixture()
def work_dir(tmp_path):
    return tmp_path
