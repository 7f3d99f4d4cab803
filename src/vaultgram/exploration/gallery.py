"""The gallery: one self-contained HTML page with a card per variant (``DIR/index.html``).

Each card holds the variant's thumbnail (inline SVG, :mod:`.thumbnail`), its metrics and a link to
its decomposition; a few lines of inline script sort the cards by any metric (a select and a
direction button) without any network access. Variants on the Pareto front carry the class
``pareto`` (a coloured frame and a badge naming the two metrics).
"""

from __future__ import annotations

import html

SHOWN = ("score", "min_scaled_jacobian", "mean_scaled_jacobian", "patches", "singularities", "poles", "edge_groups",
         "boundary_singularities", "inverted_faces", "angle_deviation_deg", "max_thrust", "zmax")

_STYLE = """body{font-family:system-ui,sans-serif;margin:1.5em;background:#f6f7f9;color:#1f2933}
#cards{display:flex;flex-wrap:wrap;gap:12px}
.card{background:#fff;border:2px solid #d9dee4;border-radius:6px;padding:8px;width:220px}
.card.pareto{border-color:#d35400}.badge{color:#d35400;font-weight:600;font-size:12px}
table{font-size:12px;border-collapse:collapse;width:100%}td{padding:1px 4px}td.v{text-align:right}
h2{font-size:14px;margin:4px 0}.error{color:#c0392b;font-size:12px}"""

_SCRIPT = """function sortCards(){var key=document.getElementById('key').value,
down=document.getElementById('dir').dataset.down==='1',box=document.getElementById('cards');
var cards=Array.prototype.slice.call(box.children);cards.sort(function(a,b){
var x=parseFloat(a.dataset[key]),y=parseFloat(b.dataset[key]);if(isNaN(x))x=-Infinity;if(isNaN(y))y=-Infinity;
return down?(y-x)||(a.dataset.id-b.dataset.id):(x-y)||(a.dataset.id-b.dataset.id);});
cards.forEach(function(c){box.appendChild(c);});}
function flip(){var b=document.getElementById('dir');b.dataset.down=b.dataset.down==='1'?'0':'1';
b.textContent=b.dataset.down==='1'?'descending':'ascending';sortCards();}"""


def _data_key(metric: str) -> str:
    """A metric's ``data-`` attribute name (HTML lowercases them; dataset reads them back as is)."""
    return metric.replace("_", "")


def _card(row: dict, svg: str, pareto: tuple) -> str:
    """One variant's card."""
    m = row["metrics"]
    data = " ".join(f'data-{_data_key(k)}="{m[k]}"' for k in SHOWN if isinstance(m.get(k), (int, float)))
    cells = "".join(f"<tr><td>{k}</td><td class=\"v\">{html.escape(str(m[k]))}</td></tr>" for k in SHOWN if k in m)
    badge = f'<div class="badge">Pareto front ({html.escape(" / ".join(pareto))})</div>' if row["pareto"] else ""
    error = f'<div class="error">{html.escape(m["error"])}</div>' if "error" in m else ""
    link = f'<a href="{row["folder"]}/decomposition.json">decomposition</a>' if "error" not in m else ""
    return (f'<div class="card{" pareto" if row["pareto"] else ""}" data-id="{row["id"]}" {data}>'
            f'<h2>variant {row["id"]}</h2>{svg}{badge}{error}<table>{cells}</table>{link}</div>')


def gallery_html(name: str, rows: list[dict], svgs: list[str], pareto: tuple) -> str:
    """The page (module docstring) for the variants ``rows`` (as in ``state_space.json``) and their
    thumbnails.

    >>> page = gallery_html("a plan", [{"id": 0, "folder": "variants/v000", "pareto": True,
    ...                                 "metrics": {"score": 1.0}}], ["<svg></svg>"], ("score", "poles"))
    >>> page.count('class="card pareto"'), "http" in page.replace("http://www.w3.org", "")
    (1, False)
    """
    options = "".join(f'<option value="{_data_key(k)}">{k}</option>' for k in SHOWN)
    cards = "".join(_card(row, svg, pareto) for row, svg in zip(rows, svgs))
    title = html.escape(f"{name}: {len(rows)} variants")
    return (f"<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>{title}</title><style>{_STYLE}</style>"
            f"</head><body><h1>{title}</h1><p>Sort by <select id=\"key\" onchange=\"sortCards()\">{options}</select> "
            f"<button id=\"dir\" data-down=\"1\" onclick=\"flip()\">descending</button>; framed: the Pareto front "
            f"over {html.escape(' and '.join(pareto))}.</p><div id=\"cards\">{cards}</div>"
            f"<script>{_SCRIPT}\nsortCards();</script></body></html>\n")
