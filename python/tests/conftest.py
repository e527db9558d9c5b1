"""Where the tests find the repository, the `kepler` command and the shared meshes.

A test that needs the command or a mesh that is missing is skipped with the reason, or fails
when KEPLER_REQUIRE_MODELS=1 (as CI runs) says it must be there.
"""

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _require():
    return os.environ.get("KEPLER_REQUIRE_MODELS") == "1"


def _missing(what):
    if _require():
        pytest.fail(f"{what} (KEPLER_REQUIRE_MODELS=1 requires it)")
    pytest.skip(what)


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def kepler_bin():
    """The command to compare with: $KEPLER_BIN, the workspace's release build, or PATH."""
    for candidate in (os.environ.get("KEPLER_BIN"), ROOT / "target/release/kepler"):
        if candidate and Path(candidate).is_file():
            return str(candidate)
    found = shutil.which("kepler")
    if found:
        return found
    _missing("no kepler command: set KEPLER_BIN or cargo build --release -p kepler-hsr-cli")


@pytest.fixture(scope="session")
def models():
    """The shared meshes: $KEPLER_MODELS or ../shared/models beside the checkout."""
    where = os.environ.get("KEPLER_MODELS")
    path = Path(where) if where else ROOT.parent / "shared" / "models"
    if not path.is_dir():
        _missing(f"no shared models at {path}")
    return path


@pytest.fixture
def model(models):
    def find(name):
        path = models / name
        if not path.is_file():
            _missing(f"no model {path}")
        return path

    return find
