"""The README's Python example runs as written."""

import os


def test_the_readme_python_example_runs(monkeypatch, capsys):
    from conftest import ROOT

    readme = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    block = readme.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)
    exec(compile(block, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert "(1000, 8, 4)" in printed
