"""`check --format sarif|github|gitlab` as the CI systems read them.

SARIF is validated with Microsoft's SARIF multitool (the validator GitHub's own documentation points
to) and with the official SARIF 2.1.0 JSON schema (the copy the multitool's npm package ships); the
GitLab report against a schema of the fields GitLab's Code Quality documentation requires; the GitHub
workflow commands against the command syntax of the runner. Every format is compared with the JSON
format of the same run: the same findings at the same lines and columns.
"""

import json
import re
import shutil
import subprocess
from pathlib import Path

import jsonschema
import pytest

from conftest import REPO, run_check

# Programs with findings of each kind the formats must carry: an error with a fix, warnings with
# fixes, a non-ASCII name and non-ASCII text before a finding (columns count characters).
PROGRAMS = {
    "programs/Teil Ä.MPF": "; Maß\nN10 G1 X10 F=AC(100)\nN20 S=IC(100)\n",
    "programs/sub/GOOD.SPF": "N10 G0 X0 Y0\nN20 M17\n",
    "programs/review.mpf": (REPO / "fixtures/examples/review_me.mpf").read_text(encoding="utf-8"),
}

# The fields GitLab's Code Quality documentation requires of every issue (severity from its list).
GITLAB_SCHEMA = {
    "type": "array",
    "items": {
        "type": "object",
        "required": ["description", "check_name", "fingerprint", "severity", "location"],
        "properties": {
            "description": {"type": "string", "minLength": 1},
            "check_name": {"type": "string", "minLength": 1},
            "fingerprint": {"type": "string", "minLength": 1},
            "severity": {"enum": ["info", "minor", "major", "critical", "blocker"]},
            "location": {
                "type": "object",
                "required": ["path", "lines"],
                "properties": {
                    "path": {"type": "string", "minLength": 1, "not": {"pattern": "^(/|\\./)"}},
                    "lines": {
                        "type": "object",
                        "required": ["begin"],
                        "properties": {"begin": {"type": "integer", "minimum": 1}},
                    },
                },
            },
        },
    },
}

GITHUB_COMMAND = re.compile(
    r"^::(?P<command>error|warning|notice) "
    r"file=(?P<file>[^,:\n]+),line=(?P<line>\d+),endLine=(?P<end_line>\d+),"
    r"col=(?P<col>\d+),endColumn=(?P<end_col>\d+),title=(?P<title>[A-Z]\d{3})::(?P<message>.+)$"
)


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    root = tmp_path_factory.mktemp("formats")
    for name, text in PROGRAMS.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root


@pytest.fixture(scope="module")
def json_findings(workspace):
    result = run_check(workspace, "json", "programs")
    assert result.returncode == 1, result.stderr
    findings = json.loads(result.stdout)
    # The programs must give what the formats are tested with: errors, warnings and fixes.
    assert {finding["severity"] for finding in findings} >= {"error", "warning"}
    assert any(finding["fix"] for finding in findings)
    assert any(finding["file"].endswith("Teil Ä.MPF") for finding in findings)
    return findings


def multitool(tools):
    return tools / "npm/node_modules/@microsoft/sarif-multitool-linux/Sarif.Multitool"


def test_sarif_is_valid_for_the_multitool_and_the_schema(workspace, json_findings, tools, tmp_path):
    result = run_check(workspace, "sarif", "programs")
    assert result.returncode == 1, result.stderr
    log_path = tmp_path / "check.sarif"
    log_path.write_text(result.stdout, encoding="utf-8")
    log = json.loads(result.stdout)

    schema_path = multitool(tools).parent / "sarif-2.1.0.json"
    schema = json.loads(schema_path.read_text(encoding="utf-8-sig"))
    jsonschema.validators.validator_for(schema)(schema).validate(log)

    report_path = tmp_path / "validation.sarif"
    validation = subprocess.run(
        [str(multitool(tools)), "validate", str(log_path), "--level", "Error;Warning;Note",
         "-o", str(report_path)],
        capture_output=True, text=True, timeout=300,
    )
    assert validation.returncode == 0, validation.stdout + validation.stderr
    report = json.loads(report_path.read_text(encoding="utf-8-sig"))
    problems = [
        (item["ruleId"], item.get("level", "warning"), item["message"].get("arguments"))
        for item in report["runs"][0]["results"]
        if item.get("level", "warning") in ("error", "warning")
    ]
    # The one warning allowed: the tool has no public web address to give as `informationUri`.
    allowed = [("SARIF2005", "warning", ["runs[0].tool.driver", "sinumerik-lsp"])]
    assert problems == allowed, problems


def test_sarif_carries_the_findings_rules_and_fixes(workspace, json_findings):
    log = json.loads(run_check(workspace, "sarif", "programs").stdout)
    run = log["runs"][0]
    rules = run["tool"]["driver"]["rules"]
    assert run["columnKind"] == "unicodeCodePoints"
    assert run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == workspace.as_uri() + "/"
    assert run["invocations"][0] == {"executionSuccessful": True, "exitCode": 1}

    s107 = next(rule for rule in rules if rule["id"] == "S107")
    assert s107["defaultConfiguration"]["level"] == "error"
    assert s107["help"]["text"].startswith(s107["shortDescription"]["text"])
    s140 = next(rule for rule in rules if rule["id"] == "S140")
    assert s140["properties"]["alarms"] == ["12060"]
    assert "12060" in s140["help"]["text"]

    results = run["results"]
    assert len(results) == len(json_findings)
    levels = {"error": "error", "warning": "warning", "info": "note", "hint": "note"}
    for result, finding in zip(results, json_findings):
        assert result["ruleId"] == finding["code"]
        assert rules[result["ruleIndex"]]["id"] == finding["code"]
        assert result["level"] == levels[finding["severity"]]
        assert result["message"]["text"] == finding["message"]
        location = result["locations"][0]["physicalLocation"]
        assert location["artifactLocation"]["uriBaseId"] == "%SRCROOT%"
        # The URI, percent-decoded, is the path JSON names.
        uri = location["artifactLocation"]["uri"]
        decoded = re.sub(r"%([0-9A-F]{2})", lambda m: chr(int(m.group(1), 16)), uri)
        assert decoded.encode("latin-1").decode("utf-8") == finding["file"]
        region = location["region"]
        assert (region["startLine"], region["startColumn"], region["endLine"], region["endColumn"]) == (
            finding["line"], finding["column"], finding["end_line"], finding["end_column"])
        if finding["fix"]:
            fix = result["fixes"][0]
            assert fix["description"]["text"] == finding["fix"]["title"]
            replacements = fix["artifactChanges"][0]["replacements"]
            for replacement, edit in zip(replacements, finding["fix"]["edits"], strict=True):
                assert replacement["insertedContent"]["text"] == edit["new_text"]
                assert replacement["deletedRegion"]["startColumn"] == edit["column"]
                assert replacement["deletedRegion"]["endColumn"] == edit["end_column"]
        else:
            assert "fixes" not in result
    # The non-ASCII file: `F=AC(100)` starts at character 14 of line 2.
    assert any(r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
               == "programs/Teil%20%C3%84.MPF" for r in results)


def test_an_incomplete_run_says_so_in_sarif(workspace):
    result = run_check(workspace, "sarif", "programs", "missing-folder")
    assert result.returncode == 2
    log = json.loads(result.stdout)
    assert log["runs"][0]["invocations"][0] == {"executionSuccessful": False, "exitCode": 2}


def test_github_commands_annotate_each_finding(workspace, json_findings):
    result = run_check(workspace, "github", "programs")
    assert result.returncode == 1, result.stderr
    lines = result.stdout.splitlines()
    *commands, summary = lines
    assert summary.startswith("checked 3 files: "), summary
    assert len(commands) == len(json_findings)
    kinds = {"error": "error", "warning": "warning", "info": "notice", "hint": "notice"}
    for command, finding in zip(commands, json_findings):
        match = GITHUB_COMMAND.match(command)
        assert match, command
        assert match["command"] == kinds[finding["severity"]]
        assert match["file"] == finding["file"]
        assert int(match["line"]) == finding["line"] == int(match["end_line"])
        assert int(match["col"]) == finding["column"]
        assert int(match["end_col"]) == max(finding["end_column"] - 1, finding["column"])
        assert match["title"] == finding["code"]
        assert match["message"].startswith(finding["message"].replace("%", "%25"))
        if finding["fix"]:
            assert match["message"].endswith(f"(fix: {finding['fix']['title']})")


def test_gitlab_report_has_the_required_fields(workspace, json_findings):
    result = run_check(workspace, "gitlab", "programs")
    assert result.returncode == 1, result.stderr
    report = json.loads(result.stdout)
    jsonschema.validate(report, GITLAB_SCHEMA)
    assert len(report) == len(json_findings)
    fingerprints = [issue["fingerprint"] for issue in report]
    assert len(set(fingerprints)) == len(fingerprints)
    severities = {"error": "major", "warning": "minor", "info": "info", "hint": "info"}
    for issue, finding in zip(report, json_findings):
        assert issue["check_name"] == finding["code"]
        assert issue["location"]["path"] == finding["file"]
        assert issue["location"]["lines"]["begin"] == finding["line"]
        assert issue["severity"] == severities[finding["severity"]]
        assert finding["message"] in issue["description"]

    # Lines inserted above the findings: the same fingerprints (GitLab tracks findings by them).
    moved = workspace.parent / (workspace.name + "-moved")
    shutil.copytree(workspace, moved)
    target = moved / "programs/review.mpf"
    target.write_text("; a comment\n; another\n" + target.read_text(encoding="utf-8"), encoding="utf-8")
    moved_report = json.loads(run_check(moved, "gitlab", "programs").stdout)
    assert [issue["fingerprint"] for issue in moved_report] == fingerprints
    assert [issue["location"]["lines"]["begin"] for issue in moved_report] != [
        issue["location"]["lines"]["begin"] for issue in report]


@pytest.mark.parametrize("output_format", ["sarif", "github", "gitlab"])
def test_exit_codes_do_not_depend_on_the_format(workspace, output_format):
    assert run_check(workspace, output_format, "programs/sub").returncode == 0
    assert run_check(workspace, output_format, "programs").returncode == 1
    assert run_check(workspace, output_format, "nothing-here").returncode == 2
