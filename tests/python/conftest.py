# Fixtures of the Python module's tests. Run by ctest (python.pytest) with the build's module on
# PYTHONPATH and TS_CLI / TS_SHARED_DATA_DIR set; by hand:
#   PYTHONPATH=build/python TS_CLI=build/treesketch /usr/bin/python3 -m pytest tests/python
import os
import pathlib
import subprocess

import numpy as np
import pytest

import treesketch

REPO = pathlib.Path(__file__).resolve().parents[2]


def shared_data_dir():
    d = os.environ.get("TS_SHARED_DATA_DIR") or str(REPO.parent / "shared" / "data")
    return pathlib.Path(d)


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("TS_CLI") or str(REPO / "build" / "treesketch")
    if not os.path.exists(path):
        pytest.skip("the treesketch command is not built (TS_CLI)")
    return path


def run_cli(cli, *args):
    """Runs the CLI; returns (exit code, stdout, the error message of its one stderr line)."""
    p = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    message = p.stderr.strip().removeprefix("treesketch: error: ")
    return p.returncode, p.stdout, message


@pytest.fixture(scope="session")
def tree_mesh():
    """The built-in 'sparse' tree, Z up: (vertices, faces)."""
    return treesketch.generate_tree("sparse", up="z")


@pytest.fixture(scope="session")
def tree_cloud_path(tmp_path_factory, tree_mesh):
    """A sphere scan of the sparse tree (about 4k points), written as .xyz."""
    cloud = treesketch.scan(tree_mesh, subdivisions=5, up="z", seed=3)
    path = tmp_path_factory.mktemp("cloud") / "tree.xyz"
    cloud.write(str(path))
    return path


@pytest.fixture(scope="session")
def tree_cloud(tree_cloud_path):
    return treesketch.read_cloud(str(tree_cloud_path))


@pytest.fixture(scope="session")
def big_cloud(tree_mesh):
    """A denser scan of the same tree (about 250k points): a reconstruction of about half a second."""
    return treesketch.scan(tree_mesh, subdivisions=8, up="z", seed=4)


@pytest.fixture(scope="session")
def tree_model(tree_cloud):
    return treesketch.reconstruct(tree_cloud)


@pytest.fixture
def line_cloud_path(tmp_path):
    """Points on one line: a cloud from which no model can be made."""
    path = tmp_path / "line.xyz"
    t = np.linspace(0, 1, 50)
    np.savetxt(path, np.column_stack([t, t, t]))
    return path
