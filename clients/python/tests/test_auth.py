"""The token, from the client's arguments, a file or the environment; and a full queue."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

import tribosim

from conftest import ENDLESS, Server, serve

TOKEN = "pytest-token-3f1a"


@pytest.fixture(scope="module")
def token_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("token") / "token"
    path.write_text(TOKEN + "\nthe second line is not read\n")
    return path


@pytest.fixture(scope="module")
def guarded(tmp_path_factory: pytest.TempPathFactory, token_file: Path) -> Iterator[Server]:
    """A server with a token, one worker and room for one queued job."""
    yield from serve(
        tmp_path_factory.mktemp("guarded"),
        ["--token-file", str(token_file), "--workers", "1", "--queue-capacity", "1"],
    )


@pytest.fixture(autouse=True)
def no_token_in_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("TRIBOSIM_TOKEN", "TRIBOSIM_TOKEN_FILE", "TRIBOSIM_URL"):
        monkeypatch.delenv(name, raising=False)


def test_without_a_token(guarded: Server) -> None:
    with tribosim.Client(guarded.url) as client:
        assert client.health() == "ok"
        assert "openapi" in client.openapi()
        with pytest.raises(tribosim.AuthError) as refused:
            client.presets()
        assert refused.value.status == 401


def test_a_wrong_token(guarded: Server) -> None:
    with tribosim.Client(guarded.url, token="wrong") as client, pytest.raises(tribosim.AuthError):
        client.jobs.list()


def test_the_token_given(guarded: Server) -> None:
    with tribosim.Client(guarded.url, token=TOKEN) as client:
        assert client.presets()


def test_the_token_from_a_file(guarded: Server, token_file: Path) -> None:
    with tribosim.Client(guarded.url, token_file=token_file) as client:
        assert client.presets()


def test_the_token_from_the_environment(guarded: Server, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("TRIBOSIM_TOKEN", TOKEN)
    with tribosim.Client(guarded.url) as client:
        assert client.presets()
    with tribosim.Client(guarded.url, token="wrong") as client, pytest.raises(tribosim.AuthError):
        client.presets()


def test_the_token_file_from_the_environment(
    guarded: Server, token_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("TRIBOSIM_TOKEN_FILE", str(token_file))
    with tribosim.Client(guarded.url) as client:
        assert client.presets()


def test_the_url_from_the_environment(guarded: Server, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("TRIBOSIM_URL", guarded.url)
    with tribosim.Client(token=TOKEN) as client:
        assert client.base_url == guarded.url
        assert client.presets()


def test_a_full_queue(guarded: Server) -> None:
    # One job runs and one waits: a third has no room (jobs that never end, so none frees
    # a place while the test runs).
    with tribosim.Client(guarded.url, token=TOKEN) as client:
        accepted: list[tribosim.Job] = []
        with pytest.raises(tribosim.RateLimitedError) as full:
            for _ in range(3):
                accepted.append(client.jobs.submit(ENDLESS))
        assert 1 <= len(accepted) <= 2
        assert full.value.status == 429
        assert full.value.retry_after_s is not None and full.value.retry_after_s >= 1
        for job in accepted:
            job.delete()
