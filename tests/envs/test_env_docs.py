"""docs/environments.md is generated from the task docstrings and YAML files
(scripts/make_env_docs.py) and must be up to date."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_environments_doc_is_up_to_date():
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_env_docs.py"), "--check"],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr


def test_every_builtin_task_has_a_section():
    text = (ROOT / "docs" / "environments.md").read_text()
    for env_id in ("Billiards-PotOne-v1", "Billiards-RunOut-v1", "Billiards-NineBall-v1"):
        assert f"## {env_id}" in text
    assert "| a1 | cue draw" in text and "Autoreset" in text
