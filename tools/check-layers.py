#!/usr/bin/env python3
"""Checks sward's layer rules (docs/architecture.md) over the source tree; exits 1 naming every violation.

- A file in a layer folder includes project headers only from its own folder or from the layers it may use.
- Vulkan headers (<vulkan/...>, <volk.h>) appear only in engine/, render/ and tools/.
- No C++ source or header is longer than 600 lines, and no function body longer than about 100 lines.

usage: tools/check-layers.py [SOURCE_ROOT]
"""
import pathlib
import re
import sys

# Each layer and the project folders its files may include (besides its own). "shared" is shaders/shared/, the
# numbers and GPU structs the CPU and GPU share.
ALLOWED = {
    "common": set(),
    "io": {"common"},
    "world": {"common", "io"},
    "vegetation": {"common", "io", "world", "shared"},
    "interaction": {"common", "io", "world", "vegetation", "shared"},
    "scene": {"common", "io", "world", "vegetation", "interaction", "shared"},
    "dataset": {"common", "io", "world", "vegetation", "interaction", "scene", "shared"},
    "eval": {"common", "io", "dataset", "shared"},
    "export": {"common", "io", "dataset"},
    "range": {"common", "io", "world", "vegetation", "interaction", "scene", "dataset", "shared"},
    "engine": {"common", "shared"},
    "render": {"common", "io", "world", "vegetation", "interaction", "scene", "dataset", "range", "engine", "shared"},
    # the Python module sits beside tools/ at the top: bindings to any layer, never to a tool's code
    "python": {"common", "io", "world", "vegetation", "interaction", "scene", "dataset", "eval", "range", "engine", "render",
               "shared"},
}
VULKAN_FREE = {"common", "io", "world", "vegetation", "interaction", "scene", "dataset", "eval", "export", "range"}
MAX_LINES = 600
MAX_FUNCTION_LINES = 110  # "about 100": a function that needs more is split into named steps

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
VULKAN_HEADER = re.compile(r"^(vulkan/|volk\.h|vk_mem_alloc\.h|imgui_impl_vulkan\.h)")


def check(root: pathlib.Path) -> list[str]:
    problems = []
    sources = [p for p in root.rglob("*") if p.suffix in {".h", ".hpp", ".cpp"} and not _ignored(root, p)]
    for path in sorted(sources):
        rel = path.relative_to(root)
        text = path.read_text(encoding="utf-8", errors="replace")
        lines = text.count("\n")
        if lines > MAX_LINES:
            problems.append(f"{rel}: {lines} lines (at most {MAX_LINES})")
        problems += [f"{rel}:{line}: function of {n} lines (at most {MAX_FUNCTION_LINES}): {head}"
                     for line, n, head in long_functions(text)]
        layer = rel.parts[0]
        if layer not in ALLOWED or len(rel.parts) != 2:
            continue
        for kind, name in INCLUDE.findall(text):
            if kind == "<" and layer in VULKAN_FREE and VULKAN_HEADER.match(name):
                problems.append(f"{rel}: includes <{name}>, but {layer}/ is Vulkan-free")
            if kind != '"' or "/" not in name:
                continue
            target = name.split("/")[0]
            if target != layer and target in ALLOWED.keys() | {"shared"} and target not in ALLOWED[layer]:
                problems.append(f'{rel}: includes "{name}", but {layer}/ may not use {target}/')
    return problems


TYPE_OR_NAMESPACE = re.compile(r"^(namespace|struct|class|enum|union|extern|template\s*<[^>]*>\s*(struct|class))\b")


def long_functions(text: str):
    """Function bodies at namespace scope: from a line ending in '{' at brace depth 0 to the line that closes
    it. Namespaces do not count as depth; types are skipped (their out-of-line members are counted)."""
    out, depth, start, head = [], 0, None, ""
    for number, line in enumerate(text.split("\n"), 1):
        code = line.split("//")[0].rstrip()
        stripped = code.strip()
        if depth == 0 and (stripped.startswith("namespace") or stripped.startswith("extern \"C\"")) and stripped.endswith("{"):
            continue
        if depth == 0 and stripped.startswith("}") and start is None:
            continue  # the end of a namespace
        if start is None and depth == 0 and stripped.endswith("{") and not TYPE_OR_NAMESPACE.match(stripped):
            start, head = number, stripped[:70]
        depth += code.count("{") - code.count("}")
        if start is not None and depth <= 0:
            if number - start + 1 > MAX_FUNCTION_LINES:
                out.append((start, number - start + 1, head))
            start, depth = None, 0
    return out


def _ignored(root: pathlib.Path, path: pathlib.Path) -> bool:
    top = path.relative_to(root).parts[0]
    return top.startswith(".") or top.startswith("build") or top in {"out"}


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    problems = check(root)
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check-layers: {len(problems)} problem(s)", file=sys.stderr)
        return 1
    print("check-layers: layers, Vulkan-free folders and file lengths are as documented")
    return 0


if __name__ == "__main__":
    sys.exit(main())
