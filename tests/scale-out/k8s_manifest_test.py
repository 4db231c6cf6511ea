#!/usr/bin/env python3
"""docs/scale-out.md's Kubernetes Indexed Job is a valid batch/v1 Job and renders shard INDEX/completions.

The YAML block is taken out of the doc (so the two cannot drift), converted to JSON and type-checked by the
TypeScript compiler as a `Job` of kubernetes-types (the Kubernetes 1.30 API types generated from its OpenAPI
spec): unknown fields at any depth (excess-property check), wrong value types and missing required fields are
errors. Both npm packages are pinned by tests/scale-out/k8s/package-lock.json and installed by
tools/setup-deps.sh (npm ci); the check itself runs offline. A canary copy of the manifest with one misspelt
field must be rejected, so a checker that accepts everything fails this test. The checks the types cannot
express (enum values, how the index reaches the command) are made here directly.

Usage: k8s_manifest_test.py --doc docs/scale-out.md --packages tests/scale-out/k8s/node_modules
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import yaml


class TestFailure(Exception):
    pass


def extract_job(doc_path):
    with open(doc_path, encoding="utf-8") as f:
        blocks = [b for b in re.findall(r"```yaml\n(.*?)```", f.read(), re.S) if re.search(r"^kind: Job$", b, re.M)]
    if len(blocks) != 1:
        raise TestFailure(f"{doc_path}: expected one ```yaml block with 'kind: Job', found {len(blocks)}")
    return yaml.safe_load(blocks[0])


def check_semantics(job):
    """What kubernetes-types leaves as plain strings and numbers."""
    spec = job["spec"]
    pod = spec["template"]["spec"]
    problems = []
    if spec.get("completionMode") != "Indexed":
        problems.append(f"spec.completionMode is {spec.get('completionMode')!r}, not 'Indexed'")
    if "backoffLimitPerIndex" in spec and pod.get("restartPolicy") != "Never":
        problems.append("backoffLimitPerIndex needs template.spec.restartPolicy: Never")
    command = " ".join(pod["containers"][0].get("command", []) + pod["containers"][0].get("args", []))
    shard = f'--shard "${{JOB_COMPLETION_INDEX}}/{spec.get("completions")}"'
    if shard not in command:
        problems.append(f"the container command does not pass {shard} (completions must be the shard count)")
    if problems:
        raise TestFailure("\n".join(problems))


def type_check(job, packages):
    """Runs tsc on the manifest and on a canary with a misspelt field; returns the canary's errors."""
    tsc = os.path.join(packages, "typescript", "bin", "tsc")
    types = os.path.join(packages, "kubernetes-types", "batch", "v1")
    node = shutil.which("node")
    if node is None or not os.path.exists(tsc) or not os.path.exists(types + ".d.ts"):
        raise TestFailure(f"node, {tsc} or {types}.d.ts missing: run tools/setup-deps.sh (npm ci in "
                          f"{os.path.dirname(packages)})")
    canary = json.loads(json.dumps(job))
    canary["spec"]["completionsMode"] = canary["spec"].pop("completionMode")
    with tempfile.TemporaryDirectory(prefix="sward-k8s-") as tmp:
        for name, obj in (("manifest", job), ("canary", canary)):
            with open(os.path.join(tmp, name + ".ts"), "w") as f:
                f.write(f'import type {{ Job }} from "{types}";\n'
                        f"export const job: Job = {json.dumps(obj, indent=2)};\n")
        result = subprocess.run([node, tsc, "--noEmit", "--strict", "--pretty", "false",
                                 "manifest.ts", "canary.ts"], cwd=tmp, capture_output=True, text=True)
    errors = result.stdout.splitlines()
    manifest_errors = [e for e in errors if e.startswith("manifest.ts")]
    canary_errors = [e for e in errors if e.startswith("canary.ts")]
    if manifest_errors or result.returncode not in (0, 2) or len(manifest_errors) + len(canary_errors) != len(errors):
        raise TestFailure("the manifest is not a valid batch/v1 Job (line numbers count in its JSON form):\n"
                          + (result.stdout + result.stderr).strip())
    if not any("completionsMode" in e for e in canary_errors):
        raise TestFailure("tsc accepted a Job with the unknown field spec.completionsMode: the check is not strict\n"
                          + result.stdout)
    return canary_errors


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--doc", required=True)
    parser.add_argument("--packages", required=True, help="node_modules with typescript and kubernetes-types")
    args = parser.parse_args()
    job = extract_job(args.doc)
    check_semantics(job)
    canary = type_check(job, os.path.abspath(args.packages))
    print(f"k8s: {args.doc}'s Job type-checks as kubernetes-types batch/v1 Job; canary rejected: {canary[0]}")


if __name__ == "__main__":
    try:
        main()
    except TestFailure as e:
        print(f"FAIL: {e}", file=sys.stderr)
        sys.exit(1)
