# The example script runs on a real cloud and writes its picture.
import os
import subprocess
import sys

import pytest

from conftest import REPO, shared_data_dir


def test_taper_example_writes_a_png(tmp_path):
    cloud = shared_data_dir() / "real" / "adtree_tree7.xyz"
    if not cloud.exists():
        pytest.skip(f"{cloud} absent")
    out = tmp_path / "taper.png"
    p = subprocess.run([sys.executable, str(REPO / "examples" / "python" / "taper.py"), str(cloud), "-o", str(out)],
                       capture_output=True, text=True, env=dict(os.environ))
    assert p.returncode == 0, p.stderr
    assert "DBH" in p.stdout and "taper:" in p.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
