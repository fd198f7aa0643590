"""The documentation site (mkdocs.yml, docs/) builds with `mkdocs build --strict`:
every link, anchor and generated results/ file it refers to resolves, and every
nav entry becomes a page. Needs the `docs` extra (mkdocs-material)."""
import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.skipif(
    importlib.util.find_spec("mkdocs") is None or importlib.util.find_spec("material") is None,
    reason="mkdocs / mkdocs-material not installed (pip install mkdocs-material; CI installs it)",
)


def _nav_files(nav):
    """The Markdown files named in an mkdocs `nav` (nested lists / one-key dicts)."""
    for item in nav:
        if isinstance(item, str):
            yield item
        elif isinstance(item, dict):
            for value in item.values():
                if isinstance(value, str):
                    yield value
                else:
                    yield from _nav_files(value)


def _page_path(site: Path, md: str) -> Path:
    stem = md[:-len(".md")]
    name = Path(stem).name
    if name in ("index", "README"):
        return site / Path(stem).parent / "index.html"
    return site / stem / "index.html"  # use_directory_urls (the default)


@pytest.fixture(scope="module")
def built_site(tmp_path_factory):
    site = tmp_path_factory.mktemp("site")
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1")
    out = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(ROOT / "mkdocs.yml"),
         "--site-dir", str(site)],
        cwd=ROOT, capture_output=True, text=True, timeout=600, env=env)
    assert out.returncode == 0, f"mkdocs build --strict failed:\n{out.stdout}\n{out.stderr}"
    return site


def test_site_has_index_and_a_page_per_nav_entry(built_site):
    import yaml

    class _Loader(yaml.SafeLoader):
        pass

    # mkdocs.yml may use tags such as !!python/name or !ENV: ignore them here.
    _Loader.add_multi_constructor("", lambda loader, suffix, node: None)
    config = yaml.load((ROOT / "mkdocs.yml").read_text(), Loader=_Loader)

    assert (built_site / "index.html").is_file()
    nav = list(_nav_files(config["nav"]))
    assert nav, "mkdocs.yml has no nav"
    for md in nav:
        assert (ROOT / "docs" / md).is_file(), f"nav entry {md} has no docs/{md}"
        assert _page_path(built_site, md).is_file(), f"no page built for nav entry {md}"
    # Every page in docs/ is in the nav (the build also warns, so fails, otherwise).
    pages = {p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").rglob("*.md")}
    assert pages <= set(nav), f"pages missing from the nav: {sorted(pages - set(nav))}"


def test_results_files_are_served_in_place(built_site):
    # The hook docs/hooks/results.py serves results/ from where the scripts write it.
    assert (built_site / "results" / "benchmark" / "benchmark" / "index.html").is_file()
    assert (built_site / "results" / "accuracy" / "accuracy.png").is_file()
    assert not (built_site / "hooks").exists()
