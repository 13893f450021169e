"""Generated code of derived expressions: equal to lambdify, built once, served from disk."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from strapdown.analysis.core import cache


@pytest.fixture
def fresh(tmp_path, monkeypatch):
    monkeypatch.setenv("STRAPDOWN_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(cache, "_memory", {})
    return tmp_path


def test_generated_code_matches_lambdify(fresh):
    x, y, z = sp.symbols("x y z", real=True)
    exprs = (sp.sin(x) * sp.exp(-y) + sp.Rational(1, 3) * sp.sqrt(z), sp.atan2(y, x) + sp.pi, sp.cos(x) ** 2 * sp.sin(x) ** 2)
    f = cache.compiled("test:tuple", lambda: ((x, y, z), exprs))
    g = sp.lambdify((x, y, z), exprs, "numpy")
    rng = np.random.default_rng(0)
    args = rng.uniform(0.1, 2.0, size=(3, 50))
    for a, b in zip(f(*args), g(*args)):
        np.testing.assert_allclose(a, b, rtol=1e-14)


def test_matrix_and_unicode_symbols(fresh):
    th, ph = sp.symbols("ϑ \\varphi")
    m = sp.Matrix([[sp.cos(th), -sp.sin(th)], [sp.sin(th) * ph, sp.cos(th) + ph]])
    f = cache.compiled("test:matrix", lambda: ((th, ph), m))
    np.testing.assert_allclose(f(0.3, 2.0), np.array(m.subs({th: 0.3, ph: 2.0}).evalf(), dtype=float), rtol=1e-15)


def test_build_runs_once_then_disk_serves(fresh, monkeypatch):
    x = sp.Symbol("x")
    calls = []

    def build():
        calls.append(1)
        return (x,), x**2 + 1

    assert cache.compiled("test:once", build)(3.0) == 10.0
    files = list(fresh.rglob("*.py"))
    assert len(files) == 1 and "# key: test:once" in files[0].read_text()
    monkeypatch.setattr(cache, "_memory", {})  # a new process: memory empty, disk warm
    assert cache.compiled("test:once", build)(2.0) == 5.0
    assert calls == [1]


def test_a_file_for_another_key_is_not_served(fresh, monkeypatch):
    x = sp.Symbol("x")
    cache.compiled("test:a", lambda: ((x,), x + 1))
    path = cache._file_for("test:a")
    monkeypatch.setattr(cache, "_file_for", lambda key: path)  # force a collision
    monkeypatch.setattr(cache, "_memory", {})
    assert cache.compiled("test:b", lambda: ((x,), x + 2))(1.0) == 3.0


def test_unwritable_cache_falls_back_to_memory(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("STRAPDOWN_CACHE_DIR", str(blocker))
    monkeypatch.setattr(cache, "_memory", {})
    x = sp.Symbol("x")
    assert cache.compiled("test:ro", lambda: ((x,), 2 * x))(4.0) == 8.0


def test_directory_is_keyed_by_version_and_source(fresh):
    from strapdown.analysis import __version__

    name = cache.cache_directory().name
    assert name.startswith(__version__ + "-") and cache.source_fingerprint()[:16] in name


def test_bad_arguments(fresh):
    with pytest.raises(TypeError, match="`key`"):
        cache.compiled("", lambda: None)
    with pytest.raises(TypeError, match="`build`"):
        cache.compiled("k", 3)


def test_derived_result_built_once_then_served_from_disk(fresh, monkeypatch):
    x, y = sp.symbols("x y", positive=True)
    calls = []

    def build():
        calls.append(1)
        return {"expr": sp.Rational(1, 60) * x**4 * sp.exp(-y), "order": 4}

    first = cache.derived("test:derived", build)
    monkeypatch.setattr(cache, "_memory", {})  # as in another process
    second = cache.derived("test:derived", build)
    assert calls == [1] and second == first and second["expr"].free_symbols == {x, y}
    assert sp.latex(second["expr"]) == sp.latex(first["expr"])  # what a report prints is unchanged


def test_derived_rebuilds_a_damaged_or_foreign_entry(fresh, monkeypatch):
    cache.derived("test:damaged", lambda: 1)
    (path,) = list(cache.cache_directory().glob("*.pickle"))
    path.write_bytes(path.read_bytes()[:-3])  # truncated
    monkeypatch.setattr(cache, "_memory", {})
    assert cache.derived("test:damaged", lambda: 2) == 2
    path.write_bytes(b"# key: another\n" + path.read_bytes().split(b"\n", 1)[1])
    monkeypatch.setattr(cache, "_memory", {})
    assert cache.derived("test:damaged", lambda: 3) == 3


def test_derived_unpicklable_result_is_returned_uncached(fresh):
    value = cache.derived("test:lambda", lambda: (lambda t: t + 1))
    assert value(1) == 2 and not list(cache.cache_directory().glob("*.pickle"))
    with pytest.raises(TypeError, match="key"):
        cache.derived("", lambda: 1)
    with pytest.raises(TypeError, match="build"):
        cache.derived("test:x", 1)


def test_a_build_may_use_the_cache_itself(fresh):
    x = sp.Symbol("x")
    inner = lambda: cache.compiled("test:inner", lambda: ((x,), 2 * x))(3.0)  # noqa: E731
    assert cache.derived("test:outer", lambda: float(inner()) + 1.0) == 7.0
