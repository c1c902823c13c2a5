"""The README / issue Markdown subset: the markup our content uses, and nothing unsafe."""

from apps.microhub.markup import render_markdown


def test_headings_lists_code_and_inline_markup():
    html = render_markdown(
        "# Title\n\nSome **bold** and `code`.\n\n- [x] done\n- [ ] open\n\n1. one\n2. two\n\n"
        "```bash\nnpm install <pkg>\n```"
    )
    assert "<h1>Title</h1>" in html
    assert "<strong>bold</strong>" in html and "<code>code</code>" in html
    assert '<li class="task"><input type="checkbox" disabled checked' in html
    assert "<ol><li>one</li><li>two</li></ol>" in html
    assert "<pre><code>npm install &lt;pkg&gt;</code></pre>" in html


def test_raw_html_is_escaped_and_only_safe_links_are_kept():
    html = render_markdown(
        "<script>alert(1)</script> [docs](docs/api.md) [x](javascript:alert(1)) "
        '[ok](https://example.com "t")'
    )
    assert "<script>" not in html and "&lt;script&gt;" in html
    assert '<a href="docs/api.md" rel="nofollow noopener">docs</a>' in html
    assert "javascript:" not in html.split("x")[0] and 'href="javascript' not in html


def test_lines_of_a_paragraph_keep_their_breaks():
    assert render_markdown("first\nsecond") == "<p>first<br>second</p>"


def test_relative_links_open_the_file_they_name_in_the_folder_of_the_text():
    """Finding: the README's `docs/api.md` link led to a bare 404."""
    files = "/r/t/microhub/blob/"
    assert 'href="/r/t/microhub/blob/docs/api.md"' in render_markdown("[api](docs/api.md)", files)
    inside = "/r/t/microhub/blob/docs"
    assert 'href="/r/t/microhub/blob/README.md"' in render_markdown("[up](../README.md)", inside)
    assert 'href="/r/t/microhub/blob/x.md"' in render_markdown("[far](../../../x.md)", inside)
    assert 'href="#usage"' in render_markdown("[usage](#usage)", files)  # anchors stay
    assert 'href="https://example.com"' in render_markdown("[ext](https://example.com)", files)
    assert 'href="docs/api.md"' in render_markdown("[api](docs/api.md)")  # no folder: as written
