#!/usr/bin/python3
"""The code cites docs that exist (CONTRIBUTING.md, docs/README.md).

Checks, over the tracked files of the checkout:
  1. every relative Markdown link or image in a .md file ([text](path), [text](path#anchor),
     [text](#anchor)) names a file or folder that exists, and its anchor a heading of that page
     (GitHub's heading ids);
  2. every `docs/...` path cited anywhere (code comments, scripts, tests, tables) exists, and its
     `#anchor` too; a path followed by a placeholder (`docs/figures/wp_<problem>.png`,
     `docs/stability/${name}.csv`) must be the start of at least one tracked path;
  3. a page named without its folder (`work_precision.md`) is a tracked file, and one under docs/
     when a section title follows;
  4. a cited page followed by a quoted section title (`docs/evidence/splitting.md, "The splitting's
     fixed point"`) has a heading, or a paragraph's bold lead, that begins with that title;
  5. every `design.md N` citation names a section N of docs/design.md, and every `method notes 1`
     or `2, section N` a section of docs/method/fluid.md or particles-and-conformation.md;
  6. nothing cites the team's notes outside the repository (the shared reference folder): what the
     code cites lives in the repository (docs/method/, docs/sources/).
Prints each broken citation as FILE:LINE: message; exit status 1 when any, 77 outside a git
checkout (the tracked files are unknown). No network. Run: scripts/check_doc_links.py [--root DIR]
(DIR: another checkout, as tests/unit/doc_links_test.sh does; default: this one).
"""

import functools
import os
import re
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
# Text files that may cite docs (binary figures and data tables are not read).
TEXT_SUFFIXES = (".md", ".cc", ".h", ".py", ".sh", ".txt", ".toml", ".js", ".html", ".cmake",
                 ".proto", ".css", ".yml", ".yaml", ".json", ".in", ".supp")
MD_LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
DOCS_PATH = re.compile(r"(?<![\w./-])docs/[\w./-]*(?:#[\w-]+)?")
OUTSIDE = re.compile(r"(?<![\w/])(?:\.\./)?shared/(?:reference|method|ops|paper|design)\S*")
METHOD_CITE = re.compile(r"method notes ([12]),? (?:sections? |part |)(\d+(?:\.\d+)*)")
METHOD_NOTES = {"1": "docs/method/fluid.md", "2": "docs/method/particles-and-conformation.md"}
BARE_PAGE = re.compile(r"(?<![\w./-])([\w-]+\.md)\b")
DESIGN_CITE = re.compile(r"design\.md(?: section)? (\d+(?:\.\d+)*)")
PLACEHOLDER_START = ("<", "$", "*", "{", "%")
# Pages that moved (issue 39): the hint a broken citation of the old path gets.
MOVED = {
    "docs/work_precision.md": "docs/evidence/work_precision.md, particle_boundary.md (e), "
                              "cut_cell_boundary.md, constraint_coupling.md or splitting.md",
    "docs/validation.md": "docs/evidence/validation.md (fluid, polymer), validation_particles.md "
                          "or validation_paper.md (the paper's section 5)",
    "docs/stability.md": "docs/evidence/stability.md",
    "docs/performance.md": "docs/evidence/performance.md",
}
# Files that name broken citations on purpose: the checker's own test (its small checkout) and
# the checker (the old paths of MOVED).
FIXTURES = {"tests/unit/doc_links_test.sh", "scripts/check_doc_links.py"}


def tracked_files():
    try:
        out = subprocess.run(["git", "-C", ROOT, "ls-files", "-z"], check=True,
                             capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    return [p for p in out.decode().split("\0") if p]


def slug(heading):
    """GitHub's id of a heading: markup and punctuation dropped, lower case, spaces to '-'."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links keep their text
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def norm(text):
    text = text.replace("`", "").replace("*", "")
    return re.sub(r"\s+", " ", text).strip().rstrip(".,:;").lower()


def titles_of(path, cache={}):
    """The headings and the bold leads of a page's paragraphs, normalised."""
    if path not in cache:
        titles, fenced = [], False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                if fenced:
                    continue
                m = re.match(r"^#{1,6}\s+(.*?)\s*$", line)
                if m:
                    titles.append(norm(m.group(1)))
                m = re.match(r"^\s*(?:[-*] |\d+\. |\|\s*)?\*\*(.+?)(?:\*\*|$)", line)
                if m:
                    titles.append(norm(m.group(1)))
        cache[path] = titles
    return cache[path]


def cites_title(page, quoted):
    want = norm(quoted)
    for title in titles_of(os.path.join(ROOT, page)):
        if title.startswith(want) or (len(title) >= 12 and want.startswith(title)):
            return True
    return False


def anchors_of(path, cache={}):
    if path not in cache:
        ids, seen, fenced = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                m = None if fenced else re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
                if m:
                    base = slug(m.group(2))
                    n = seen.get(base, 0)
                    seen[base] = n + 1
                    ids.add(base if n == 0 else f"{base}-{n}")
                for name in re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
                    ids.add(name)
        cache[path] = ids
    return cache[path]


def check_target(target_path, anchor, tracked_set, tracked_dirs):
    """None when the target (repository-relative) exists with its anchor, else the reason."""
    rel = os.path.normpath(target_path)
    if rel not in tracked_set and rel not in tracked_dirs:
        moved = f" (moved: {MOVED[rel]}; docs/README.md maps them)" if rel in MOVED else ""
        return f"{rel} does not exist{moved}"
    if anchor:
        if not rel.endswith(".md"):
            return None
        if anchor not in anchors_of(os.path.join(ROOT, rel)):
            return f"{rel} has no heading #{anchor}"
    return None


@functools.lru_cache(maxsize=None)
def numbered_sections(page):
    """The numbers of a page's numbered headings ("## 3.", "### 3.1", "## Part 2.")."""
    sections = set()
    path = os.path.join(ROOT, page)
    if not os.path.exists(path):
        return sections
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"^#{2,4}\s+(?:Part\s+)?(\d+(?:\.\d+)*)\.?\s", line)
            if m:
                sections.add(m.group(1))
    return sections


def design_sections():
    return numbered_sections("docs/design.md")


def check_markdown_links(path, lines, tracked_set, tracked_dirs, errors):
    fenced = False
    for number, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            continue
        for target in MD_LINK.findall(re.sub(r"`[^`]*`", "", line)):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            file_part, _, anchor = target.partition("#")
            if file_part:
                full = os.path.join(os.path.dirname(path), file_part)
                if os.path.isabs(file_part):
                    errors.append(f"{path}:{number}: absolute link {target}")
                    continue
            else:
                full = path
            reason = check_target(full, anchor, tracked_set, tracked_dirs)
            if reason:
                errors.append(f"{path}:{number}: link {target}: {reason}")


QUOTED_TITLE = re.compile(r"^(?:'s)?(?: \([a-e]\))?,? (?:section )?\(?\"([^\")+\s][^\"]*)\"")
COMMENT_LEAD = re.compile(r"\n\s*(?://+|#+|\*|--|%)?\s*")


def check_quoted_title(path, number, lines, end, page, errors):
    after = COMMENT_LEAD.sub(" ", "\n".join([lines[number - 1][end:]] + lines[number:number + 2]))
    quoted = QUOTED_TITLE.match(after)
    if quoted and not cites_title(page, quoted.group(1)):
        errors.append(f'{path}:{number}: cites {page}, "{quoted.group(1)}": '
                      f"no heading or bold lead of that page begins so")


def check_bare_pages(path, lines, basenames, errors):
    """Pages named without their folder: they exist; under docs/, a quoted title follows them."""
    for number, line in enumerate(lines, 1):
        for m in BARE_PAGE.finditer(line):
            candidates = basenames.get(m.group(1), [])
            if not candidates:
                errors.append(f"{path}:{number}: names {m.group(1)}, which is no tracked file")
                continue
            in_docs = [c for c in candidates if c.startswith("docs/")]
            if len(in_docs) == 1:
                check_quoted_title(path, number, lines, m.end(), in_docs[0], errors)


def check_cited_paths(path, lines, tracked, tracked_set, tracked_dirs, sections, errors):
    for number, line in enumerate(lines, 1):
        for m in DOCS_PATH.finditer(line):
            cited = m.group(0)
            file_part, _, anchor = cited.partition("#")
            following = line[m.end():m.end() + 1]
            if following and following in PLACEHOLDER_START or file_part.endswith("_"):
                if not any(p.startswith(file_part) for p in tracked):
                    errors.append(f"{path}:{number}: no tracked path starts with {file_part}")
                continue
            file_part = file_part.rstrip(".")
            reason = check_target(file_part, anchor, tracked_set, tracked_dirs)
            if reason:
                errors.append(f"{path}:{number}: cites {cited}: {reason}")
            elif file_part.endswith(".md"):
                check_quoted_title(path, number, lines, m.end(), file_part, errors)
        for outside in OUTSIDE.findall(line):
            errors.append(f"{path}:{number}: cites {outside}, outside the repository (bring it "
                          f"into docs/)")
        for note, section in METHOD_CITE.findall(line):
            if section not in numbered_sections(METHOD_NOTES[note]):
                errors.append(f"{path}:{number}: cites method notes {note}, section {section}, "
                              f"not a section of {METHOD_NOTES[note]}")
        for section in DESIGN_CITE.findall(line):
            if section not in sections:
                errors.append(f"{path}:{number}: cites design.md {section}, not a section of "
                              f"docs/design.md ({', '.join(sorted(sections))})")


def main():
    global ROOT
    if len(sys.argv) == 3 and sys.argv[1] == "--root":
        ROOT = os.path.abspath(sys.argv[2])
    elif len(sys.argv) != 1:
        print("usage: check_doc_links.py [--root DIR]", file=sys.stderr)
        return 2
    tracked = tracked_files()
    if tracked is None:
        print("check_doc_links: not a git checkout (the tracked files are unknown)",
              file=sys.stderr)
        return 77
    tracked = [p for p in tracked if os.path.exists(os.path.join(ROOT, p))]
    tracked_set = set(tracked)
    tracked_dirs = {os.path.dirname(p) for p in tracked}
    for d in list(tracked_dirs):
        while d:
            d = os.path.dirname(d)
            tracked_dirs.add(d)
    sections = design_sections()
    basenames = {}
    for p in tracked:
        basenames.setdefault(os.path.basename(p), []).append(p)
    errors = []
    checked = 0
    for path in tracked:
        if (not path.endswith(TEXT_SUFFIXES) or path.startswith("docs/figures/")
                or path in FIXTURES):
            continue
        try:
            with open(os.path.join(ROOT, path), encoding="utf-8") as f:
                lines = f.read().split("\n")
        except UnicodeDecodeError:
            continue
        checked += 1
        if path.endswith(".md"):
            check_markdown_links(path, lines, tracked_set, tracked_dirs, errors)
        check_cited_paths(path, lines, tracked, tracked_set, tracked_dirs, sections, errors)
        check_bare_pages(path, lines, basenames, errors)
    if errors:
        print(f"check_doc_links: {len(errors)} broken citations:", file=sys.stderr)
        for e in errors:
            print("  " + e, file=sys.stderr)
        return 1
    print(f"check_doc_links: every link and docs/ path in {checked} files resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
