"""What is shipped: the release workflow and the CI snippets of docs/cli.md through actionlint (they
cannot run here), `cargo install --locked --path .` into a temporary root, and the VS Code package
that `npm run package` wrote (tests/run-all.sh packages it before these tests): under 5 MB, with the
dist build of the server inside.
"""

import os
import re
import struct
import subprocess
import tomllib
import zipfile

import pytest
import yaml

from conftest import REPO

VERSION = tomllib.loads((REPO / "Cargo.toml").read_text())["package"]["version"]
PACKAGE = REPO / "editors/vscode/dist/sinumerik-lsp.vsix"
MAX_PACKAGE_BYTES = 5_000_000


def actionlint(tools, cwd, *files):
    return subprocess.run(
        [str(tools / "venv/bin/actionlint"), "-color=false", *files],
        cwd=cwd, capture_output=True, text=True, timeout=300,
        env={**os.environ, "PATH": f"{tools / 'venv/bin'}{os.pathsep}{os.environ['PATH']}"},
    )


def snippet(document, heading):
    """The first ```yaml block after the paragraph that starts with `heading`."""
    start = document.index(heading)
    match = re.compile(r"```yaml\n(.*?)```", re.S).search(document, start)
    return match.group(1)


def test_the_workflows_pass_actionlint(tools):
    workflows = sorted((REPO / ".github/workflows").glob("*.yml"))
    assert any(path.name == "release.yml" for path in workflows)
    result = actionlint(tools, REPO, *[str(path.relative_to(REPO)) for path in workflows])
    assert result.returncode == 0, result.stdout + result.stderr


def test_actionlint_finds_a_broken_workflow(tools, tmp_path):
    # The check is only worth something if actionlint rejects what GitHub would: an unknown runner
    # label and an expression on a context that does not exist.
    release = (REPO / ".github/workflows/release.yml").read_text()
    broken = release.replace("ubuntu-22.04-arm", "ubuntu-20.40").replace(
        "matrix.rust-target", "matrix.rust_targte", 1)
    (tmp_path / ".github/workflows").mkdir(parents=True)
    (tmp_path / ".github/workflows/release.yml").write_text(broken)
    subprocess.run(["git", "init", "-q", "."], cwd=tmp_path, check=True)
    result = actionlint(tools, tmp_path)
    assert result.returncode == 1
    assert "ubuntu-20.40" in result.stdout and "rust_targte" in result.stdout, result.stdout


def test_the_release_builds_every_platform_with_the_dist_profile():
    workflow = yaml.safe_load((REPO / ".github/workflows/release.yml").read_text())
    build = workflow["jobs"]["build"]
    targets = {entry["vscode-target"] for entry in build["strategy"]["matrix"]["include"]}
    assert {"linux-x64", "win32-x64", "darwin-x64", "darwin-arm64"} <= targets
    commands = "\n".join(step.get("run", "") for step in build["steps"])
    assert "--profile dist" in commands
    assert "--target \"$SINUMERIK_LSP_BUNDLE_TARGET\"" in commands


def test_the_ci_snippets_of_the_documentation_are_valid(tools, tmp_path):
    document = (REPO / "docs/cli.md").read_text()
    github = snippet(document, "GitHub Actions (")
    (tmp_path / ".github/workflows").mkdir(parents=True)
    (tmp_path / ".github/workflows/nc-programs.yml").write_text(github)
    subprocess.run(["git", "init", "-q", "."], cwd=tmp_path, check=True)
    result = actionlint(tools, tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "check --format github" in github and "check --format sarif" in github

    gitlab = yaml.safe_load(snippet(document, "GitLab CI ("))
    job = gitlab["nc-programs"]
    report = job["artifacts"]["reports"]["codequality"]
    assert any(f"check --format gitlab . > {report}" in line for line in job["script"])
    assert job["artifacts"]["when"] == "always"

    hooks = yaml.safe_load(snippet(document, "repository of programs:"))
    hook_ids = {hook["id"] for hook in hooks["repos"][0]["hooks"]}
    listed = {hook["id"] for hook in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())}
    assert hook_ids <= listed


def test_cargo_install_locked_puts_a_working_binary_in_the_root(tmp_path):
    # The release profile's artifacts in target/ are reused: cargo install copies the binary.
    env = {**os.environ, "CARGO_TARGET_DIR": str(REPO / "target")}
    root = tmp_path / "root"
    install = subprocess.run(
        ["cargo", "install", "--locked", "--path", ".", "--root", str(root)],
        cwd=REPO, env=env, capture_output=True, text=True, timeout=1800,
    )
    assert install.returncode == 0, install.stderr
    installed = root / "bin" / ("sinumerik-lsp.exe" if os.name == "nt" else "sinumerik-lsp")
    version = subprocess.run([str(installed), "--version"], capture_output=True, text=True)
    assert version.stdout == f"sinumerik-lsp {VERSION}\n"


def elf_section_names(data):
    """The section names of a 64-bit little-endian ELF file (enough to tell a stripped binary)."""
    assert data[:4] == b"\x7fELF" and data[4] == 2 and data[5] == 1, "not a 64-bit little-endian ELF"
    section_offset, = struct.unpack_from("<Q", data, 0x28)
    entry_size, count, names_index = struct.unpack_from("<HHH", data, 0x3A)
    headers = [data[section_offset + i * entry_size: section_offset + (i + 1) * entry_size]
               for i in range(count)]
    names_offset, = struct.unpack_from("<Q", headers[names_index], 0x18)
    names = []
    for header in headers:
        name_at, = struct.unpack_from("<I", header, 0)
        end = data.index(b"\0", names_offset + name_at)
        names.append(data[names_offset + name_at:end].decode())
    return names


def test_the_vscode_package_is_small_and_bundles_the_dist_build(tmp_path):
    if not PACKAGE.is_file():
        pytest.fail(f"{PACKAGE} is missing: run `npm run package` in editors/vscode first")
    size = PACKAGE.stat().st_size
    print(f"{PACKAGE.name}: {size / 1e6:.2f} MB")
    assert size < MAX_PACKAGE_BYTES, f"{size} bytes"
    with zipfile.ZipFile(PACKAGE) as package:
        names = package.namelist()
        servers = [name for name in names if name.startswith("extension/server/")]
        assert servers == ["extension/server/linux-x64/sinumerik-lsp"], servers
        binary = package.read(servers[0])
    sections = elf_section_names(binary)
    assert ".text" in sections
    # The dist build: no debug information and no symbol table.
    assert not [name for name in sections if name.startswith(".debug") or name == ".symtab"], sections
    extracted = tmp_path / "sinumerik-lsp"
    extracted.write_bytes(binary)
    extracted.chmod(0o755)
    version = subprocess.run([str(extracted), "--version"], capture_output=True, text=True)
    assert version.stdout == f"sinumerik-lsp {VERSION}\n"


def test_the_elf_reader_sees_debug_sections_of_the_release_build():
    # The release build keeps line tables (debug = 1): the reader above must see them, or the check
    # of the package would pass on any binary.
    release = REPO / "target/release/sinumerik-lsp"
    if not release.is_file():
        pytest.fail(f"{release} is missing: run `cargo build --release` first")
    sections = elf_section_names(release.read_bytes())
    assert ".debug_line" in sections and ".symtab" in sections
