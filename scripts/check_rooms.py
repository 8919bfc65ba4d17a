#!/usr/bin/env python3
"""Checks that every include in the code follows the room order of docs/ARCHITECTURE.md.

The order is the fenced block tagged `rooms` in that file: one level per line, bottom first;
rooms on one line are siblings. A file may include its own room and rooms on lower levels,
never a sibling or a room above; `never:` lines forbid further pairs (the planners never see
the reference). Every source file of sim/, policies/, viz/ and apps/ must stand in a listed
room. Usage: check_rooms.py [ROOT]; exit 1 with one line per violation, 0 when all is well.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
CHECKED_TOPS = ("sim", "policies", "viz", "apps")


def read_order(root):
    doc = (root / "docs" / "ARCHITECTURE.md").read_text()
    m = re.search(r"^```rooms\n(.*?)^```", doc, re.M | re.S)
    if not m:
        sys.exit("docs/ARCHITECTURE.md: no ```rooms block")
    level_of, never = {}, []
    level = 0
    for raw in m.group(1).splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if line.startswith("never:"):
            src, dst = [s.strip() for s in line[len("never:"):].split("->")]
            never.append((src, dst))
            continue
        for room in line.split():
            level_of[room] = level
        level += 1
    return level_of, never


def room_of(path, level_of):
    """The longest listed room that is `path` or a folder holding it."""
    best = None
    for room in level_of:
        if path == room or path.startswith(room.rstrip("/") + "/"):
            if best is None or len(room) > len(best):
                best = room
    return best


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    level_of, never = read_order(root)
    problems = []
    for top in CHECKED_TOPS:
        for f in sorted((root / top).rglob("*")):
            if f.suffix not in (".h", ".cpp") or not f.is_file():
                continue
            rel = f.relative_to(root).as_posix()
            src = room_of(rel, level_of)
            if src is None:
                problems.append(f"{rel}: stands in no room of docs/ARCHITECTURE.md")
                continue
            text = f.read_text()
            for n, inc in enumerate(INCLUDE.findall(text)):
                line = text[: text.find(f'"{inc}"')].count("\n") + 1
                dst = room_of(inc, level_of)
                if dst is None:
                    if inc.split("/")[0] in CHECKED_TOPS:
                        problems.append(f"{rel}:{line}: includes {inc}, which stands in no room")
                    continue
                if dst == src:
                    continue
                if level_of[dst] >= level_of[src]:
                    how = "a sibling" if level_of[dst] == level_of[src] else "a room above"
                    problems.append(f"{rel}:{line}: {src} includes {inc}: {how} ({dst})")
                for a, b in never:
                    if src.startswith(a) and dst.startswith(b):
                        problems.append(f"{rel}:{line}: {src} may never include {dst} ({inc})")
    for p in problems:
        print(p)
    if problems:
        print(f"check_rooms: {len(problems)} include(s) break the room order", file=sys.stderr)
        return 1
    print(f"check_rooms: {len(level_of)} rooms, every include follows the order")
    return 0


if __name__ == "__main__":
    sys.exit(main())
