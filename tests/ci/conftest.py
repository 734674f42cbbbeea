"""What the CI-integration tests share: the repository, the binary under test, the tool folder."""

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BINARY = Path(os.environ.get("SINUMERIK_LSP_BIN", REPO / "target/release/sinumerik-lsp"))


def run_check(cwd, output_format, *paths):
    """`check --format FORMAT PATH...` in `cwd`, as a CI job runs it from the repository's root."""
    return subprocess.run(
        [str(BINARY), "check", "--format", output_format, *paths],
        cwd=cwd, capture_output=True, text=True, encoding="utf-8", timeout=120,
    )


@pytest.fixture(scope="session")
def tools():
    """The cached tool folder of setup-tools.sh (run.sh sets it)."""
    folder = os.environ.get("SINUMERIK_CI_TOOLS_DIR")
    assert folder, "run the tests through tests/ci/run.sh, which installs the tools"
    return Path(folder)


def pytest_sessionstart(session):
    assert BINARY.is_file(), f"{BINARY} is missing: build it with `cargo build --release`"
