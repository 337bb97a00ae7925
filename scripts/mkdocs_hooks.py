"""MkDocs hook for the bkquake documentation (mkdocs.yml, `hooks:`).

The pages are written in GitHub's markdown, which Python-Markdown (MkDocs) reads
differently in two places; this hook bridges them before a page is converted, so the
pages read the same on a repository browser and on the site:
- a list that follows a paragraph line directly needs a blank line before it, or
  Python-Markdown runs it into the paragraph;
- the generated tables escape a '|' inside a code span as '\\|', which GitHub needs and
  renders as '|'; Python-Markdown's tables already ignore a '|' inside a code span and
  would print the backslash.
"""

import re

_CODE_SPAN = re.compile(r"`[^`\n]*`")
_LIST_ITEM = re.compile(r"^(\s*)([-*+]|\d+\.) ")


def on_page_markdown(markdown, **kwargs):
    out = []
    fenced = False
    previous = ""
    for line in markdown.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        elif not fenced:
            if line.startswith("|"):
                line = _CODE_SPAN.sub(lambda m: m.group(0).replace("\\|", "|"), line)
            item = _LIST_ITEM.match(line)
            if (item and not item.group(1) and previous.strip()
                    and not _LIST_ITEM.match(previous) and not previous.startswith((" ", "\t", "|", "#"))):
                out.append("")
        out.append(line)
        previous = line
    return "\n".join(out)
