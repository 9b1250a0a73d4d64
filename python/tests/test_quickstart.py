"""examples/python/quickstart.py runs, and says what the guide says it says."""
import os
import subprocess
import sys

from conftest import SOURCE_DIR


def test_quickstart_runs():
    done = subprocess.run([sys.executable, os.path.join("examples", "python", "quickstart.py")], cwd=SOURCE_DIR,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert "dm1 = (0.1*m1^2 + 0.1*P11) dt + K1_1 (dy1 - m1 dt)" in out
    assert "m_drift [0.125]" in out
    assert "optimal" in out and "RMS" in out
    assert "equal to equations (21)-(22): True" in out
