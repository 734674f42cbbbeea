"""The hooks of .pre-commit-hooks.yaml through the real pre-commit (`pre-commit try-repo`), on a
temporary git repository with a good and a bad program: the good one passes every hook, the bad one
fails each of them with its finding in the output.

The `-system` hooks run the binary under test from PATH. The `language: rust` hooks make pre-commit
build the crate with `cargo install` from a clone of this repository, which takes minutes: the
build reuses the release artifacts of target/ through CARGO_TARGET_DIR (cargo compiles the crate
itself again, from pre-commit's clone, but not its dependencies). try-repo installs into a temporary
store, so the rust hooks are run once, all together.
"""

import os
import shutil
import subprocess
import time

import pytest
import yaml

from conftest import BINARY, REPO

GOOD = "N10 G0 X0 Y0\nN20 G1 X10 F100\nN30 M30\n"
# S101 (an error), not formatted (`g0 x0  y0`), not numbered in steps of 10 (N25).
BAD = "N10 g0 x0  y0\nN20 G1 X=AC5 F100\nN25 M30\n"
# What each hook prints about BAD.MPF.
FAILURE_TEXT = {
    "check": "BAD.MPF:2:10: error[S101]",
    "fmt": "would be reformatted: BAD.MPF",
    "renumber": "would be renumbered: BAD.MPF",
}


@pytest.fixture()
def programs(tmp_path):
    """A git repository with GOOD.MPF and BAD.MPF (staged, as pre-commit reads them)."""
    repo = tmp_path / "programs"
    repo.mkdir()
    (repo / "GOOD.MPF").write_text(GOOD)
    (repo / "BAD.MPF").write_text(BAD)
    # A file the hooks must not be given.
    (repo / "notes.txt").write_text("N10 g0 X=AC5\n")
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@example.invalid"]
    subprocess.run([*git, "init", "-q", "."], cwd=repo, check=True)
    subprocess.run([*git, "add", "."], cwd=repo, check=True)
    return repo


def try_repo(tools, cwd, hook, *files, extra_env=None):
    """`pre-commit try-repo` of this repository with one hook (`hook`) or all of them (empty)."""
    env = dict(os.environ)
    env["PATH"] = f"{BINARY.parent}{os.pathsep}{env['PATH']}"
    env.update(extra_env or {})
    args = ["--files", *files] if files else ["--all-files"]
    return subprocess.run(
        [str(tools / "venv/bin/pre-commit"), "try-repo", str(REPO), *([hook] if hook else []),
         "--color", "never", *args],
        cwd=cwd, env=env, capture_output=True, text=True, timeout=1800,
    )


def test_the_hooks_file_names_real_subcommands():
    hooks = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    ids = {hook["id"]: hook for hook in hooks}
    for name, command in [("check", "check"), ("fmt", "fmt --check"), ("renumber", "renumber --check")]:
        for hook_id, language in [(f"sinumerik-{name}", "rust"), (f"sinumerik-{name}-system", "system")]:
            assert ids[hook_id]["entry"] == f"sinumerik-lsp {command}"
            assert ids[hook_id]["language"] == language
    usage = subprocess.run([str(BINARY), "--help"], capture_output=True, text=True).stdout
    for command in ["check", "fmt [--check]", "renumber [--start N] [--step N] [--keep|--all|--drop] [--check]"]:
        assert f"sinumerik-lsp {command}" in usage


@pytest.mark.parametrize("name", ["check", "fmt", "renumber"])
def test_system_hooks_pass_good_and_fail_bad_programs(tools, programs, name):
    hook = f"sinumerik-{name}-system"
    good = try_repo(tools, programs, hook, "GOOD.MPF", "notes.txt")
    assert good.returncode == 0, good.stdout + good.stderr
    assert "Passed" in good.stdout
    bad = try_repo(tools, programs, hook, "GOOD.MPF", "BAD.MPF", "notes.txt")
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "Failed" in bad.stdout
    assert FAILURE_TEXT[name] in bad.stdout, bad.stdout
    assert "notes.txt" not in bad.stdout


def test_rust_hooks_build_the_tool_and_report_findings(tools, programs):
    """One try-repo run of every hook on both programs: try-repo installs into a temporary store, so
    each run builds the crate again; the `-system` tests above show that the same entries pass the
    good program, this one that the built tool runs and fails the bad one with its findings."""
    if shutil.which("cargo") is None:
        pytest.fail("cargo is needed to install the language: rust hooks")
    started = time.monotonic()
    run = try_repo(tools, programs, "", "GOOD.MPF", "BAD.MPF", "notes.txt",
                   extra_env={"CARGO_TARGET_DIR": str(REPO / "target")})
    print(f"language: rust hooks, install and run: {time.monotonic() - started:.0f} s")
    assert run.returncode == 1, run.stdout + run.stderr
    # Every hook ran and failed (the rust ones and the system ones alike), each with its finding.
    for name in ["check", "fmt", "renumber"]:
        title = f"sinumerik-lsp {'check' if name == 'check' else name + ' --check'}"
        failed = [line for line in run.stdout.splitlines() if line.startswith(title) and "Failed" in line]
        assert len(failed) == 2, run.stdout
        assert run.stdout.count(FAILURE_TEXT[name]) == 2, run.stdout
    assert "notes.txt" not in run.stdout
