"""Static assets on versioned URLs with a year's immutable caching; old URLs and pages revalidated."""
from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import PLOTLY_DIR, app
from server.api.static_files import IMMUTABLE, content_version

ASSET = re.compile(r'(?:src|href)="(/(?:static|vendor)/[^"]+)"')


@pytest.fixture(scope="module")
def client() -> TestClient:
    return TestClient(app)


@pytest.mark.parametrize("page", ["/", "/scenes/transfer-functions", "/scenes/equation-of-motion"])
def test_a_pages_assets_are_versioned_and_immutable_and_the_page_is_revalidated(client, page):
    answer = client.get(page)
    assert answer.status_code == 200 and answer.headers["cache-control"] == "no-cache"
    assets = ASSET.findall(answer.text)
    assert assets and all(re.match(r"/(static/[0-9a-f]{12}|vendor/plotly/[\d.]+)/", url) for url in assets)
    for url in assets:
        asset = client.get(url)
        assert asset.status_code == 200 and asset.headers["cache-control"] == IMMUTABLE, url


def test_a_relative_module_import_stays_under_the_version_and_old_urls_are_revalidated(client):
    scene_js = next(u for u in ASSET.findall(client.get("/scenes/transfer-functions").text) if u.endswith("_scene.js"))
    imported = scene_js.rsplit("/", 2)[0] + "/common/model/api.js"     # import … from "../common/model/api.js"
    assert client.get(imported).headers["cache-control"] == IMMUTABLE
    for old in ("/static/js/common/model/api.js", "/vendor/plotly/plotly.min.js"):
        answer = client.get(old)
        assert answer.status_code == 200 and answer.headers["cache-control"] == "no-cache"
    assert client.get("/static/0123456789ab/js/common/model/api.js").status_code == 404   # not today's version


def test_the_version_changes_with_any_file_name_or_content(tmp_path):
    (tmp_path / "js").mkdir()
    (tmp_path / "js" / "a.js").write_text("export const a = 1;\n")
    (tmp_path / "app.css").write_text("body {}\n")
    first = content_version(tmp_path)
    assert content_version(tmp_path) == first
    (tmp_path / "js" / "a.js").write_text("export const a = 2;\n")
    changed = content_version(tmp_path)
    (tmp_path / "js" / "a.js").rename(tmp_path / "js" / "b.js")
    renamed = content_version(tmp_path)
    assert len({first, changed, renamed}) == 3 and re.fullmatch(r"[0-9a-f]{12}", first)


def test_text_files_come_gzipped_from_one_compressed_copy(client):
    url = next(u for u in ASSET.findall(client.get("/scenes/transfer-functions").text) if u.endswith("plotly.min.js"))
    first, second = (client.get(url, headers={"accept-encoding": "gzip"}) for _ in range(2))
    original = (PLOTLY_DIR / "plotly.min.js").read_bytes()
    for answer in (first, second):
        assert answer.headers["content-encoding"] == "gzip" and answer.headers["cache-control"] == IMMUTABLE
        assert answer.content == original and int(answer.headers["content-length"]) < len(original) / 2
    plain = client.get(url, headers={"accept-encoding": "identity"})
    assert plain.content == original and "content-encoding" not in plain.headers
    assert client.get(url, headers={"if-none-match": first.headers["etag"]}).status_code == 304
