"""MkDocs hook: serve the generated files under ``results/`` as part of the site.

The measuring scripts write their tables, plots and data under ``results/`` at
the repository root, and the pages in ``docs/`` link to them with paths such as
``../results/benchmark/benchmark.md`` (which also work when the repository is
browsed as files). MkDocs only knows files inside ``docs_dir``, so with
``--strict`` those links would fail. This hook adds every file of the kinds
below under ``results/`` to the site *in place*: no copy is kept in ``docs/``,
the scripts stay the single source.

Each file gets the source URI ``../results/<path>`` (relative to ``docs_dir``),
which is exactly what MkDocs resolves a page's ``../results/<path>`` link to,
so the links in the Markdown need no rewriting; it is written to the site at
``results/<path>`` (Markdown rendered as a page, everything else copied).
Generated tables that start without a title get one naming their source file.
"""

from __future__ import annotations

import os
import posixpath

from mkdocs.structure.files import File, Files, InclusionLevel

RESULTS = "results"
# The kinds of files the scripts write there; anything else (a stray checkpoint,
# say) is left out of the site.
SITE_SUFFIXES = {
    ".md", ".png", ".svg", ".jpg", ".jpeg", ".gif", ".html",
    ".csv", ".json", ".txt", ".yaml", ".yml",
}
# Scratch output (git-ignored), not results.
SKIP_DIRS = {"tmp"}


def _results_dir(config) -> str:
    repo_root = os.path.dirname(os.path.abspath(config.config_file_path))
    return os.path.join(repo_root, RESULTS)


def on_files(files: Files, config) -> Files:
    results_dir = _results_dir(config)
    docs_dir = config.docs_dir
    for root, dirnames, filenames in os.walk(results_dir):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".")
                             and not (root == results_dir and d in SKIP_DIRS))
        for name in sorted(filenames):
            if name.startswith(".") or os.path.splitext(name)[1].lower() not in SITE_SUFFIXES:
                continue
            rel = os.path.relpath(os.path.join(root, name), results_dir).replace(os.sep, "/")
            site_uri = posixpath.join(RESULTS, rel)
            # Where the file goes in the site, computed as if it lay in docs/results/.
            dest_uri = File(site_uri, None, config.site_dir, config.use_directory_urls).dest_uri
            files.append(
                File(
                    os.path.relpath(os.path.join(results_dir, rel), docs_dir).replace(os.sep, "/"),
                    src_dir=docs_dir,
                    dest_dir=config.site_dir,
                    use_directory_urls=config.use_directory_urls,
                    dest_uri=dest_uri,
                    # Set explicitly: the default exclusion of dot-paths would
                    # otherwise match the leading "..".
                    inclusion=InclusionLevel.NOT_IN_NAV,
                )
            )
    return files


def on_page_markdown(markdown: str, page, config, files) -> str:
    src = page.file.src_uri
    if src.startswith("../" + RESULTS + "/") and not markdown.lstrip().startswith("# "):
        return f"# `{src[3:]}`\n\n{markdown}"
    return markdown
