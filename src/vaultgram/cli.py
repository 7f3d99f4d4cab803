"""The ``vaultgram`` command line.

Every user mistake (a bad rule file, an invalid graph or domain, a strategy that does not terminate)
is printed as one line naming the problem and where it is, with exit code 2 and no traceback; a
command writes its files in a staging folder and moves them into --out only when all are written
(:func:`vaultgram.io.files.output_folder`), so a failed or interrupted run leaves --out untouched.
"""

from __future__ import annotations

import contextlib
import gc
import json
import os
import sys
import warnings
from pathlib import Path

import click

from vaultgram import progress
from vaultgram.clitypes import FINITE, ITERATIONS, Finite, max_faces_option, spacing_option
from vaultgram.errors import VaultgramError, VaultgramWarning
from vaultgram.io.files import output_folder, read_json, write_json, write_text


class _Group(click.Group):
    """A click group that turns a VaultgramError, or a bad option of a command, into one line on
    stderr and exit code 2."""

    def invoke(self, ctx):
        """Run the command; a VaultgramWarning (what an input had that was not used) is one
        ``warning:`` line after it, or folded into the error line if it fails; other libraries'
        warnings (numpy, shapely) are dropped: what they warn of is checked and named."""
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("ignore")
            warnings.simplefilter("always", VaultgramWarning)
            try:
                result = super().invoke(ctx)
            except VaultgramError as exc:
                click.echo(f"error: {exc}{_folded(caught)}", err=True)
                sys.exit(2)
            except click.UsageError as exc:
                _usage_line(exc)
        for w in caught:
            click.echo(f"warning: {w.message}", err=True)
        return result

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        """click's ``main``, with its usage errors (the group's own too: an unknown command or option)
        as one line naming the command, instead of click's usage block."""
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode, **extra)
        _PROCESS["program"] = args is None  # the program's own run; a caller's (a test's) passes arguments
        try:
            code = super().main(args, prog_name, complete_var, False, **extra)
        except click.UsageError as exc:
            _usage_line(exc)
        except click.ClickException as exc:
            exc.show()
            sys.exit(exc.exit_code)
        except click.Abort:
            click.echo("Aborted!", err=True)
            sys.exit(1)
        except KeyboardInterrupt:  # after the command ended (click turns one during it into Abort)
            sys.exit(130)
        except SystemError as exc:  # a signal inside a C extension's import: ended as the signal ends a run
            signalled = _signal_behind(exc)
            if signalled is None:
                raise
            if isinstance(signalled, SystemExit):
                sys.exit(signalled.code)
            click.echo("Aborted!", err=True)
            sys.exit(1)
        finally:
            if _PROCESS["program"]:
                gc.freeze()  # the process ends: no last collection over every object still alive (issue 18)
        sys.exit(code if isinstance(code, int) else 0)


def _signal_behind(exc: BaseException) -> BaseException | None:
    """The interrupt (``KeyboardInterrupt``: SIGINT) or termination (``SystemExit``: SIGTERM, which
    the staging of an output folder raises as ``SystemExit(143)``) behind a ``SystemError``, or None.

    A signal that lands while a C extension initialises (``design`` imports cvxopt's BLAS module
    lazily) raises its exception inside the extension's init function, which Python reports as
    ``SystemError: initialization of blas raised unreported exception`` with the signal's exception
    as its cause: the run then ends as that signal ends it anywhere else, without a traceback.

    >>> try:
    ...     try:
    ...         raise KeyboardInterrupt
    ...     except KeyboardInterrupt as interrupt:
    ...         raise SystemError("initialization of blas raised unreported exception") from interrupt
    ... except SystemError as exc:
    ...     type(_signal_behind(exc)).__name__, _signal_behind(SystemError("other"))
    ('KeyboardInterrupt', None)
    """
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, (KeyboardInterrupt, SystemExit)):
            return exc
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return None


#: ``program``: whether :meth:`_Group.main` runs as the program itself (its arguments from
#: ``sys.argv``), whose objects may be frozen out of the garbage collector (:func:`long_lived`), or is
#: called by other code (a test's runner, an application) whose objects must stay collectable.
_PROCESS = {"program": False}


@contextlib.contextmanager
def long_lived():
    """Run a command's start-up (its imports, the rulebook) with the garbage collector paused; in the
    program's own process, then move every object into the collector's permanent generation
    (``gc.freeze``); restore the collector (issue 18). The program's own process also gets one BLAS
    thread before numpy loads (:func:`_one_blas_thread`).

    Modules, classes and the checked rulebook live as long as the process, yet collections walked
    them again and again, and once more at exit: in ``vaultgram mesh`` of a small plan the collector
    took 8.5 percent of the instructions (160 of 1,870 million, callgrind) and freed some 700 objects.
    What the command creates afterwards is collected as before.

    >>> enabled = gc.isenabled()
    >>> with long_lived():
    ...     gc.isenabled()
    False
    >>> gc.isenabled() == enabled
    True
    """
    if _PROCESS["program"]:
        _one_blas_thread()
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if _PROCESS["program"]:
            gc.freeze()
        if enabled:
            gc.enable()


#: The variables by which OpenBLAS (numpy's BLAS) takes its thread count, in its order of precedence.
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")


def _one_blas_thread() -> None:
    """Before numpy's first import, one OpenBLAS thread, unless the user chose a count (issue 18).

    numpy's OpenBLAS starts a thread per core when it loads, and they spin waiting for work: on two
    cores ``import numpy`` took 140-190 ms CPU against 90 with one thread (wall 90-160 against 90-105
    ms, the machine loaded). The commands that call this (``mesh``, ``decompose``) multiply no large
    matrices (dot products of vectors, 2 x 2 solves; the smoothing's product is numpy's ``bincount``
    or scipy's sparse one), so the threads only cost; one thread also sums those dot products in one
    order whatever the machine's cores. Only the program's own process: a caller's (a test's) is not
    changed, nor does it matter once numpy is loaded.
    """
    if "numpy" not in sys.modules and not any(os.environ.get(name) for name in BLAS_THREADS):
        os.environ["OPENBLAS_NUM_THREADS"] = "1"


def _usage_line(exc: click.UsageError) -> None:
    """A click usage error as one line, ``error: vaultgram mesh: No such option: --bogus (see
    'vaultgram mesh --help')``, and exit code 2."""
    path = exc.ctx.command_path if exc.ctx is not None else "vaultgram"
    message = " ".join(exc.format_message().split())
    click.echo(f"error: {path}: {message} (see '{path} --help')", err=True)
    sys.exit(2)


def _folded(caught) -> str:
    """The warnings before an error, folded into its line."""
    if not caught:
        return ""
    more = f" and {len(caught) - 1} more" if len(caught) > 1 else ""
    return f" (after a warning: {caught[0].message}{more})"


# Options several commands share.
POSITIVE = Finite(min=0.0, min_open=True)
OUT = click.option("--out", "out_dir", required=True, type=click.Path(file_okay=False), help="Output directory.")
SPACING = spacing_option
RULES = click.option("--rules", "rules_dir", default=None, type=click.Path(file_okay=False, exists=True),
                     help="Directory with the rule files: topology.vgr, tessellation.vgr "
                          "(default: the rulebook shipped with vaultgram).")
TARGET_LENGTH = click.option("--target-length", type=POSITIVE, default=None,
                             help="Target mesh edge length (domain units); "
                                  "default 2.5% of the bounding-box diagonal.")
SMOOTH = click.option("--smooth", default=None, type=ITERATIONS,
                      help="Laplacian smoothing iterations "
                           "(default 20; 0: the raw Coons patches, not untangled either).")
ALLOW_FOLDS = click.option("--allow-folds", is_flag=True,
                           help="Write a mesh that still has inverted faces (with a warning) instead of failing.")
THRUST = [
    click.option("--zmax", type=POSITIVE, default=None,
                 help="Height of the highest point (default: a quarter of the plan's shorter side)."),
    click.option("--thickness", type=POSITIVE, default=1.0, show_default=True, help="Shell thickness for self-weight."),
    click.option("--density", type=POSITIVE, default=1.0, show_default=True,
                 help="Material density (weight per volume)."),
    click.option("--point-load", type=FINITE, default=0.0, show_default=True,
                 help="Vertical load at every point feature (a column load, a lantern...)."),
    click.option("--tol-deg", type=POSITIVE, default=0.5, show_default=True,
                 help="Horizontal equilibrium: largest angle between form and force edges."),
    click.option("--sag", type=POSITIVE, default=0.1, show_default=True,
                 help="How far unsupported boundary edges are bent inwards before form finding (relative)."),
    click.option("--relax-mode", type=click.Choice(["auto", "boundary", "all"]), default="auto", show_default=True,
                 help="Bend only the unsupported boundary ('boundary'), let every vertex move ('all'), or the "
                      "boundary first and every vertex if that fails ('auto')."),
]


SUPPORTS = click.option("--supports", "supports_path", type=click.Path(dir_okay=False), default=None,
                        help='JSON: {"rings": [...]}, {"polylines": [...]} or {"vertices": [...]} '
                             '(overrides the input).')
DENSITIES = click.option("--densities", "densities_path", type=click.Path(dir_okay=False), default=None,
                         help="Density file: JSON {target_length, length_mode, min_count, groups, regions}.")


QUIET = click.option("--quiet", is_flag=True,
                     help="No progress on stderr (it is shown only when stderr is a terminal anyway).")
FORMAT = click.option("--format", "formats", default=None, metavar="LIST",
                      help="Output formats, comma-separated: json, obj, compas, 3dm, dxf (default: json,obj).")
INPUT_FORMAT = click.option("--input-format", type=click.Choice(["json", "geojson", "dxf", "3dm"]), default=None,
                            help="The input's format (default: by extension, then by content).")
LAYERS = click.option("--layer", "layers", multiple=True, metavar="ROLE=NAME",
                      help="A DXF or .3dm layer name for a role (outer, holes, points, curves, supports); "
                           "repeatable. Defaults: the role's own name.")


def layer_names(pairs) -> dict:
    """``--layer ROLE=NAME`` options as a dict."""
    out = {}
    for pair in pairs:
        role, sep, name = pair.partition("=")
        if not sep or not name:
            raise VaultgramError(f"--layer: expected ROLE=NAME, got {pair!r}")
        out[role.strip()] = name.strip()
    return out


def input_options(command):
    """The options of the commands that read a domain: its format and its layers."""
    return INPUT_FORMAT(LAYERS(command))


TESSELLATION = [
    click.option("--rhythm", type=click.Choice(["2", "4"]), default="2", show_default=True,
                 help="Keep every second or every fourth edge along a course (voussoirs of about 2 or 4 faces)."),
    click.option("--max-concavity", type=Finite(180.0, 360.0, max_open=True), default=190.0,
                 show_default=True, help="Largest voussoir corner (degrees, in its best-fit plane)."),
    click.option("--flat-extrados", is_flag=True, help="Make each voussoir's top face planar (best-fit plane)."),
    click.option("--surface-smooth", type=ITERATIONS, default=0, show_default=True,
                 help="Laplacian smoothing iterations of the network on the thrust surface "
                      "(no voussoir made concave)."),
]


def tessellation_options(command):
    """The tessellation options of ``tessellate`` and ``design``."""
    for option in reversed(TESSELLATION):
        command = option(command)
    return command


def thrust_options(command):
    """The form-finding options of ``formfind`` and ``design``."""
    for option in reversed(THRUST):
        command = option(command)
    return command


@click.group(cls=_Group)
@click.version_option(package_name="vaultgram")
def main() -> None:
    """vaultgram: structural patterns for masonry vaults and funicular shells."""


@main.group(cls=_Group)
def rules() -> None:
    """Check and run rule files (the graph-grammar DSL)."""


@rules.command("check")
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON.")
def rules_check(files, as_json: bool) -> None:
    """Parse and type-check rule FILES; print their types, rules, strategies and invariants. The
    tessellation's file (``tessellation.vgr``, §5) is a rulebook of its own, checked with the
    tessellation's functions, beside the topology's rulebook of the other files. A successful check is
    cached by the contents of the files and of the code that checks them (vaultgram.checked_rules)."""
    from vaultgram.checked_rules import checked_summaries

    summaries = checked_summaries(files, lambda: _rulebooks(files))
    if as_json:
        click.echo(json.dumps(summaries[0] if len(summaries) == 1 else summaries, indent=2))
        return
    for summary in summaries:
        _echo_rulebook(summary)


def _echo_rulebook(summary: dict) -> None:
    """The printed summary of one rulebook (``rules check``)."""
    types = summary["types"]
    click.echo(f"ok: {len(summary['files'])} file(s)")
    click.echo(f"node types ({len(types['nodes'])}): " + ", ".join(
        f"{n} : {p}" if p and p != "Node" else n for n, p in types["nodes"].items()))
    click.echo(f"edge types ({len(types['edges'])}): " + ", ".join(f"{n} ({d})" for n, d in types["edges"].items()))
    click.echo(f"rules ({len(summary['rules'])}):")
    for name, info in summary["rules"].items():
        params = ", ".join(info["params"])
        click.echo(f"  {name}({params}) priority {info['priority']}, {info['nacs']} NAC(s)")
    click.echo(f"strategies ({len(summary['strategies'])}):")
    for name, steps in summary["strategies"].items():
        click.echo(f"  {name}: " + "; ".join(steps))
    click.echo(f"invariants ({len(summary['invariants'])}):")
    for name, when in summary["invariants"].items():
        click.echo(f"  {name}: {when}")


def _load_graph(path: str, book):
    """A host graph from JSON; where nodes carry positions (``pos``), the cyclic order of the edges
    around each node follows the geometry (counter-clockwise, along an edge's ``polyline`` if it has
    one), as in the pipeline; elsewhere it is the order of the edge ids."""
    from vaultgram.engine.graph import HostGraph
    from vaultgram.io.strict import graph_document
    from vaultgram.topology.decomposition import edge_angle

    try:
        return HostGraph.from_json(graph_document(read_json(path)), book.schema, angle=edge_angle)
    except VaultgramError as exc:
        raise VaultgramError(exc if str(exc).startswith(f"{path}:") else f"{path}: {exc}") from None


def _load_rules(files):
    """The rulebook of rule FILES, with the functions of the stage that runs it: the tessellation's
    for its own file (``tessellation.vgr``), the vault pipeline's topology functions otherwise."""
    books = _rulebooks(files)
    if len(books) > 1:
        raise click.UsageError("tessellation.vgr is a rulebook of its own (the tessellation's, §5): "
                               "give it without the topology's rule files")
    return books[0]


def _rulebooks(files) -> list:
    """The rulebooks of rule FILES: the topology's (every file but ``tessellation.vgr``) and the
    tessellation's, each loaded with its stage's functions, those that have files."""
    from vaultgram.engine.rulebook import load_rulebook
    from vaultgram.tessellation.functions import tessellation_functions
    from vaultgram.tessellation.keystones import RULE_FILE
    from vaultgram.topology.functions import vault_functions

    topology = [f for f in files if Path(f).name != RULE_FILE]
    tessellation = [f for f in files if Path(f).name == RULE_FILE]
    return ([load_rulebook(topology, vault_functions())] if topology else []) + \
        ([load_rulebook(tessellation, tessellation_functions())] if tessellation else [])


@rules.command("run")
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--graph", "graph_path", required=True, type=click.Path(dir_okay=False),
              help="Host graph JSON: {nodes: [{id, type, ...}], edges: [{id, type, source, target, ...}]}.")
@click.option("--strategy", required=True, help="Name of the strategy to run.")
@OUT
def rules_run(files, graph_path: str, strategy: str, out_dir: str) -> None:
    """Run a STRATEGY of rule FILES on a host graph; write graph.json and trace.json to --out."""
    from vaultgram.engine.strategy import Runner

    book = _load_rules(files)
    graph = _load_graph(graph_path, book)
    runner = Runner(book, graph)
    runner.run(strategy)
    out = Path(out_dir)
    with output_folder(out) as stage:
        write_json(stage / "graph.json", graph.to_json())
        write_json(stage / "trace.json", runner.trace.to_json())
    for report in runner.reports:
        click.echo(f"{report.step}: {report.applications} application(s) in {report.seconds * 1000:.1f} ms")
    click.echo(f"wrote {out / 'graph.json'} ({len(graph)} nodes, {graph.num_edges} edges) and {out / 'trace.json'}")


@rules.command("why-not")
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--graph", "graph_path", required=True, type=click.Path(dir_okay=False))
@click.option("--rule", "rule_name", required=True, help="The rule to explain.")
@click.option("--limit", type=click.IntRange(min=1), default=10, show_default=True,
              help="How many near matches to list.")
def rules_why_not(files, graph_path: str, rule_name: str, limit: int) -> None:
    """Explain why a rule does not match a graph: its nearest partial matches (up to --limit), what
    failed in each, and the values of the attributes and calls in a failed condition."""
    from vaultgram.engine.whynot import why_not

    matcher = _matcher(files, graph_path, rule_name)
    click.echo(str(why_not(matcher, limit)))


def _matcher(files, graph_path: str, rule_name: str):
    """A matcher of rule ``rule_name`` of FILES on the graph at ``graph_path``."""
    from vaultgram.engine.matcher import Matcher
    from vaultgram.errors import RewriteError

    book = _load_rules(files)
    if rule_name not in book.rules:
        raise RewriteError(f"unknown rule '{rule_name}'")
    return Matcher(book.rules[rule_name], _load_graph(graph_path, book))


@rules.command("matches")
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--graph", "graph_path", required=True, type=click.Path(dir_okay=False))
@click.option("--rule", "rule_name", required=True, help="The rule whose matches to list.")
@click.option("--json", "as_json", is_flag=True, help="Print the matches as JSON (a list of bindings).")
def rules_matches(files, graph_path: str, rule_name: str, as_json: bool) -> None:
    """List every match of a rule in a graph (in the engine's match order), one binding a line."""
    matches = [dict(m.binding) for m in _matcher(files, graph_path, rule_name).all()]
    if as_json:
        click.echo(json.dumps(matches))
        return
    for k, binding in enumerate(matches):
        click.echo(f"{k}: " + ", ".join(f"{v}={i}" for v, i in binding.items() if not v.startswith("_")))
    click.echo(f"{len(matches)} match(es) of {rule_name}")


@rules.command("test")
@click.argument("rules_dirs", metavar="RULES...", nargs=-1, required=True, type=click.Path(exists=True))
@click.option("--examples", type=click.IntRange(min=1), default=100, show_default=True,
              help="How many random domains hypothesis draws.")
@click.option("--seed", type=int, default=None, help="Draw other examples (default: the same ones every run).")
@click.option("--out", "out_dir", default="rules-test-failure", show_default=True, type=click.Path(file_okay=False),
              help="Where a counterexample is written.")
def rules_test(rules_dirs, examples: int, seed: int | None, out_dir: str) -> None:
    """Property-test rulebooks (folders with topology.vgr, or that file) on random domains: their
    invariants after every rule application, the topology stage's checks. Exit 1 on a counterexample,
    written shrunk to --out with the command that replays it."""
    try:
        from vaultgram.testing.rulestest import check_rulebook, write_failure
    except ImportError as exc:  # hypothesis missing
        raise VaultgramError(f"rules test needs hypothesis ({exc}): pip install 'vaultgram[rulestest]'") from None
    for path in rules_dirs:
        directory = Path(path) if Path(path).is_dir() else Path(path).parent
        summary = check_rulebook(directory, examples, seed)
        if summary.failure is not None:
            with output_folder(out_dir) as stage:
                lines = write_failure(summary.failure, directory, Path(out_dir), stage)
            for line in lines:
                click.echo(line)
            sys.exit(1)
        click.echo(f"ok: {directory}: {summary.text()}")


@rules.command("replay")
@click.argument("files", nargs=-1, required=True, type=click.Path(dir_okay=False))
@click.option("--graph", "graph_path", required=True, type=click.Path(dir_okay=False),
              help="The graph the trace started from (the start_graph.json decompose --trace writes).")
@click.option("--trace", "trace_path", required=True, type=click.Path(dir_okay=False), help="trace.json.")
@OUT
def rules_replay(files, graph_path: str, trace_path: str, out_dir: str) -> None:
    """Replay a trace (rules run, decompose --trace) on its starting graph; write graph.json."""
    from vaultgram.engine.trace import load_trace, replay

    book = _load_rules(files)
    graph = _load_graph(graph_path, book)
    replayed = replay(load_trace(trace_path), book, graph)
    with output_folder(out_dir) as stage:
        write_json(stage / "graph.json", graph.to_json())
    click.echo(f"replayed {len(replayed)} application(s); wrote {Path(out_dir) / 'graph.json'} "
               f"({len(graph)} nodes, {graph.num_edges} edges)")


TRACE = click.option("--trace", "with_trace", is_flag=True,
                     help="Also write trace.json (every rule application) and start_graph.json (the graph the "
                          "rules started from), for vaultgram rules replay.")


@main.command("decompose")
@click.argument("domain_path", metavar="DOMAIN", type=click.Path(dir_okay=False))
@OUT
@SPACING
@RULES
@click.option("--smooth-branches", is_flag=True, help="Smooth the skeleton branches with splines (scipy).")
@click.option("--plot/--no-plot", default=True, show_default=True, help="Also write decomposition.png.")
@FORMAT
@input_options
@click.option("--invariants", is_flag=True, help="Check the rulebook's invariants while its strategies run.")
@TRACE
def decompose_command(domain_path: str, out_dir: str, spacing: float, rules_dir: str | None, smooth_branches: bool,
                      plot: bool, formats, input_format: str | None, layers, invariants: bool,
                      with_trace: bool) -> None:
    """Block decomposition of a DOMAIN (JSON, GeoJSON, DXF or .3dm) into 3- and 4-sided patches (paper 3.1).

    Writes decomposition.json, patches.json and decomposition.png (--format 3dm or dxf: the patches
    as closed polylines in result.3dm or result.dxf; --trace: trace.json and start_graph.json).
    """
    with long_lived():
        from vaultgram.domain import load_domain
        from vaultgram.io.outputs import parse_formats, write_decomposition, write_drawings
        from vaultgram.meshpipeline import decompose

    formats = parse_formats(formats)
    domain = load_domain(domain_path, input_format, layer_names(layers), spacing)
    dec = decompose(domain, spacing, rules_dir, smooth=smooth_branches, check_invariants=invariants, trace=with_trace)
    with output_folder(out_dir) as stage:
        write_decomposition(dec, stage, plot, formats, with_trace)
        write_drawings(stage, formats, domain.units, decomposition=dec)
    echo_decomposition(dec, Path(out_dir))


def echo_decomposition(dec, out: Path) -> None:
    """The rule steps that applied something, and the patch counts."""
    fired = [r for r in dec.reports if r.applications]
    for report in fired:
        click.echo(f"rules: {report.step}: {report.applications} application(s)")
    if len(fired) < len(dec.reports):
        click.echo(f"rules: {len(dec.reports) - len(fired)} other step(s) found nothing to do")
    counts = dec.patches_json()["counts"]
    click.echo(f"{len(dec.patches)} patches ({counts['4']} four-sided, {counts['3']} three-sided), "
               f"{len(dec.singularities())} singularities; wrote {out}")


def echo_timings(timings: dict) -> None:
    """One line with the seconds per stage (measured by the pipeline; design also writes them to timings.json)."""
    click.echo("time:       " + ", ".join(f"{k} {v * 1000:.1f} ms" for k, v in timings.items()))


@main.command("trace")
@click.argument("domain_path", metavar="DOMAIN", type=click.Path(dir_okay=False))
@OUT
@SPACING
@RULES
@click.option("--each", is_flag=True, help="A figure after each rule application, not each strategy step.")
def trace_command(domain_path: str, out_dir: str, spacing: float, rules_dir: str | None, each: bool) -> None:
    """Figures of the decomposition graph of a DOMAIN after each strategy step (or application) of the
    rules, matched elements red and created ones green, and index.html stepping through them."""
    from vaultgram.domain import load_domain
    from vaultgram.io.traceview import write_trace_view
    from vaultgram.meshpipeline import decompose
    from vaultgram.topology.rulebook import load_vault_rulebook

    dec = decompose(load_domain(domain_path), spacing, rules_dir, trace=True)
    with output_folder(out_dir) as stage:
        count = write_trace_view(dec, load_vault_rulebook(rules_dir), stage, each)
    click.echo(f"wrote {count + 1} figure(s) and {Path(out_dir) / 'index.html'}")


@main.command("formfind")
@click.argument("input_path", metavar="DOMAIN|MESH", type=click.Path(dir_okay=False))
@OUT
@thrust_options
@SUPPORTS
@SPACING
@TARGET_LENGTH
@max_faces_option
@FORMAT
@click.option("--input-format", type=click.Choice(["json", "geojson", "dxf", "3dm", "mesh", "obj", "compas"]),
              default=None, help="The input's format (default: by extension, then by content).")
@LAYERS
def formfind_command(input_path, out_dir, zmax, thickness, density, point_load, tol_deg, sag, relax_mode,
                     supports_path, spacing, target_length, formats, input_format, layers, max_faces) -> None:
    """Thrust Network Analysis (paper 5) on a MESH or a DOMAIN.

    A MESH is a mesh.json (or any {"vertices", "faces"}), a Wavefront OBJ or a COMPAS mesh JSON, faces
    of any number of sides; a DOMAIN is meshed first (as `vaultgram mesh` does). Supports: --supports,
    else the input's own (the domain's "supports", a mesh's "supports" vertex list, a COMPAS mesh's
    is_support vertices), else the outer boundary. Writes form.json, force.json, thrust.json,
    thrust.obj and summary.json to --out (see --format for the others).
    """
    from vaultgram.domain import load_domain
    from vaultgram.io.meshfiles import read_pattern
    from vaultgram.io.outputs import parse_formats, write_drawings, write_thrust
    from vaultgram.pipeline import mesh_domain, thrust_of_mesh

    formats = parse_formats(formats)
    domain = None
    timings: dict = {}
    pattern = read_pattern(input_path, input_format)  # None: a domain (mesh, obj, compas always give one)
    if pattern is not None:
        mesh, spec = pattern
    else:
        domain = load_domain(input_path, input_format, layer_names(layers), spacing)
        mesh = mesh_domain(domain, spacing, target_length, timings=timings, max_faces=max_faces)
        spec = domain.supports
    if supports_path:
        spec = read_json(supports_path)
    network = thrust_of_mesh(mesh, spec, domain, point_load, timings, zmax=zmax, thickness=thickness,
                             density=density, tol_deg=tol_deg, sag=sag, relax_mode=relax_mode)
    with output_folder(out_dir) as stage:
        write_thrust(network, stage, formats=formats)
        write_drawings(stage, formats, domain.units if domain is not None else None, network=network)
    click.echo(network.summary_text())
    echo_timings(timings)


@main.command("tessellate")
@click.argument("thrust_path", metavar="THRUST", type=click.Path(dir_okay=False))
@OUT
@click.option("--thickness", type=POSITIVE, default=1.0, show_default=True, help="Voussoir thickness.")
@tessellation_options
@RULES
@FORMAT
def tessellate_command(thrust_path, out_dir, thickness, rhythm, max_concavity, flat_extrados, surface_smooth,
                       rules_dir, formats) -> None:
    """Voussoirs from a THRUST network (thrust.json, paper 5): keystones, staggered bond, solids, courses.

    Writes tessellation.json, voussoirs.obj and summary.json to --out (see --format for the others).
    """
    from vaultgram.io.outputs import parse_formats, write_drawings, write_tessellation
    from vaultgram.pipeline import tessellate
    from vaultgram.tessellation.metrics import format_summary
    from vaultgram.tessellation.surface import surface_from_json

    formats = parse_formats(formats)
    timings: dict = {}
    surface = surface_from_json(read_json(thrust_path), thrust_path)
    result = tessellate(surface, int(rhythm), thickness, max_concavity, flat_extrados, surface_smooth, rules_dir,
                        timings)
    with output_folder(out_dir) as stage:
        write_tessellation(result, stage, summary=True, formats=formats)
        write_drawings(stage, formats, tessellation=result)
    click.echo(format_summary(result.summary))
    echo_timings(timings)


@main.command("design")
@click.argument("domain_path", metavar="DOMAIN", type=click.Path(dir_okay=False))
@OUT
@SPACING
@RULES
@TARGET_LENGTH
@SMOOTH
@DENSITIES
@ALLOW_FOLDS
@SUPPORTS
@thrust_options
@tessellation_options
@FORMAT
@input_options
@TRACE
@max_faces_option
@click.option("--plots/--no-plots", default=True, show_default=True,
              help="Write the figures of every stage (figures/*.png and *.svg, and the PNGs beside the files).")
@click.option("--report/--no-report", "with_report", default=True, show_default=True,
              help="Write report.html (figures, parameters, metrics and times of every stage in one page).")
@QUIET
def design_command(domain_path, out_dir, spacing, rules_dir, target_length, smooth, densities_path, allow_folds,
                   supports_path, zmax, thickness, density, point_load, tol_deg, sag, relax_mode, rhythm,
                   max_concavity, flat_extrados, surface_smooth, formats, input_format, layers, with_trace,
                   max_faces, plots, with_report, quiet) -> None:
    """The whole pipeline on a DOMAIN: decomposition (3.1, 4), mesh (3.2), thrust network and voussoirs (5).

    Everything is computed before anything is written, so a failing stage leaves no output. The DOMAIN
    is vaultgram JSON, GeoJSON, DXF or a Rhino .3dm; --format 3dm writes result.3dm, one layer per stage.
    """
    with progress.reporting(not quiet):
        progress.note(f"design: starting on {domain_path}")  # before the imports: a second or two
        from vaultgram.domain import load_domain
        from vaultgram.io.figures.errorplot import error_figure
        from vaultgram.io.figures.worker import FigureWorker
        from vaultgram.io.outputs import parse_formats, write_design
        from vaultgram.meshing.densities import load_densities
        from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS
        from vaultgram.pipeline import TessellationOptions, design
        from vaultgram.tessellation.metrics import format_summary

        formats = parse_formats(formats)
        domain = load_domain(domain_path, input_format, layer_names(layers), spacing)
        out = Path(out_dir)
        parameters = {k: v for k, v in click.get_current_context().params.items() if k not in ("out_dir", "quiet")}
        # the figures are drawn in the background as the stages end (vaultgram.io.figures.worker); a
        # stage failing on a geometric problem leaves its error figure alone (vaultgram.io.figures.errorplot)
        with error_figure(out, domain), output_folder(out) as stage, FigureWorker(stage, formats) as figures:
            result = design(
                domain, spacing, rules_dir, target_length, DEFAULT_ITERATIONS if smooth is None else smooth,
                load_densities(densities_path) if densities_path else None, allow_folds,
                read_json(supports_path) if supports_path else None, point_load, zmax, thickness,
                TessellationOptions(int(rhythm), max_concavity, flat_extrados, surface_smooth), trace=with_trace,
                density=density, tol_deg=tol_deg, sag=sag, relax_mode=relax_mode, max_faces=max_faces,
                on_stage=figures if plots and "json" in formats else None)
            timings = write_design(result, stage, formats, with_trace, plots, with_report, parameters, figures)
    echo_decomposition(result.decomposition, out)
    click.echo(f"mesh: {len(result.mesh.vertices)} vertices, {len(result.mesh.faces)} faces; "
               f"wrote {_joined(f for f in ('mesh.json', 'mesh.obj', 'mesh.compas.json') if _written(f, formats))}")
    click.echo(result.network.summary_text())
    click.echo(format_summary(result.tessellation.summary))
    echo_timings(timings)


@main.command("report")
@click.argument("folder", metavar="DIR", type=click.Path(file_okay=False, exists=True))
def report_command(folder) -> None:
    """Rebuild DIR/report.html from a finished `vaultgram design` output folder (its summary.json,
    timings.json and figures/*.svg)."""
    from vaultgram.io.report import report_html

    page = report_html(Path(folder))  # read and checked before anything is written
    with output_folder(folder) as stage:
        write_text(stage / "report.html", page)
    click.echo(f"wrote {Path(folder) / 'report.html'}")


def _written(name: str, formats) -> bool:
    """Whether a file of this name is written for these formats."""
    kind = "compas" if name.endswith(".compas.json") else Path(name).suffix.lstrip(".")
    return kind in formats


def _joined(names) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    names = list(names)
    return " and ".join([", ".join(names[:-1]), names[-1]]) if len(names) > 1 else "".join(names)


@main.command("mesh")
@click.argument("domain_path", metavar="DOMAIN", type=click.Path(dir_okay=False))
@OUT
@SPACING
@TARGET_LENGTH
@SMOOTH
@DENSITIES
@ALLOW_FOLDS
@SUPPORTS
@FORMAT
@input_options
@max_faces_option
@RULES
def mesh_command(domain_path, out_dir, spacing, target_length, smooth, densities_path, allow_folds,
                 supports_path, formats, input_format, layers, max_faces, rules_dir) -> None:
    """Quad-mesh a DOMAIN (paper 3): decompose, mesh the patches, weld, smooth.

    Writes mesh.json (vertices, faces, vertex labels, edge groups, the vertices that bear thrust) and
    mesh.obj to --out (see --format for the others); `vaultgram formfind mesh.json` then gives the
    thrust network `design` gives.
    """
    with long_lived():
        from vaultgram.domain import load_domain
        from vaultgram.formfinding.supports import support_vertices
        from vaultgram.io.outputs import parse_formats, write_drawings, write_mesh_files
        from vaultgram.meshing.densities import load_densities
        from vaultgram.meshing.quality import mesh_stats
        from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS
        from vaultgram.meshpipeline import mesh_domain
        from vaultgram.topology.rulebook import load_vault_rulebook

        load_vault_rulebook(rules_dir)  # the rulebook, which mesh_domain then finds loaded

    formats = parse_formats(formats)
    domain = load_domain(domain_path, input_format, layer_names(layers), spacing)
    spec = load_densities(densities_path) if densities_path else None
    mesh = mesh_domain(domain, spacing, target_length, DEFAULT_ITERATIONS if smooth is None else smooth, spec,
                       rules_dir=rules_dir, allow_folds=allow_folds, max_faces=max_faces)
    supports = read_json(supports_path) if supports_path else domain.supports
    if isinstance(supports, list):
        supports = {"vertices": supports}
    anchors = support_vertices(mesh.vertices, mesh.faces, supports, domain, mesh.origin)
    out = Path(out_dir)
    with output_folder(out) as stage:
        write_mesh_files(mesh, stage, anchors, plot=False, formats=formats)
        write_drawings(stage, formats, domain.units, mesh=mesh)
    names = [*(f for f in ("mesh.json", "mesh.obj", "mesh.compas.json") if _written(f, formats)),
             *(f"result.{f}" for f in ("3dm", "dxf") if f in formats)]
    stats = mesh_stats(mesh, domain)
    click.echo(
        f"wrote {_joined(str(out / f) for f in names)}: {stats['vertices']} vertices, {stats['quads']} quads, "
        f"{stats['triangles']} triangles; {mesh.info['patches']} patches, {mesh.info['edge_groups']} edge groups"
    )
    click.echo(
        f"singular: {stats['interior_singular']} interior, {stats['boundary_singular']} boundary; "
        f"min scaled Jacobian {stats['min_scaled_jacobian']:.3f}"
    )
    if stats["inverted_faces"]:
        click.echo(f"warning: {stats['inverted_faces']} inverted face(s): the mesh folds; try a smaller "
                   "--target-length, or move the features away from each other and from the boundary", err=True)


@main.command("stats")
@click.argument("mesh_path", metavar="MESH", type=click.Path(dir_okay=False))
@click.option("--domain", "domain_path", type=click.Path(dir_okay=False), default=None,
              help="The domain: corner angles and the boundary distance are measured against it.")
@click.option("--json", "as_json", is_flag=True, help="Print the metrics as JSON.")
def stats_command(mesh_path, domain_path, as_json) -> None:
    """Quality metrics of a MESH (mesh.json): singularities, scaled Jacobian, angles, boundary fit."""
    from vaultgram.domain import load_domain
    from vaultgram.io.meshfiles import mesh_from_json
    from vaultgram.meshing.quality import format_stats, mesh_stats

    mesh = mesh_from_json(read_json(mesh_path), mesh_path)
    domain = load_domain(domain_path) if domain_path else None
    stats = mesh_stats(mesh.in_frame(domain.origin) if domain is not None else mesh, domain)
    click.echo(json.dumps(stats, indent=1) if as_json else format_stats(stats))


# -- exploration (issue 13): vaultgram explore, vaultgram replay ---------------------------------------


@main.command("explore")
@click.argument("domain_path", metavar="DOMAIN", type=click.Path(dir_okay=False))
@OUT
@SPACING
@RULES
@click.option("--limit", default=100, show_default=True, type=int, help="States to visit at most.")
@click.option("--depth", default=8, show_default=True, type=int, help="Choice points to explore along a path.")
@click.option("--seed", default=None, type=int, help="Visit each choice point's options in an order drawn from it.")
@click.option("--order", default="breadth", show_default=True, type=click.Choice(["breadth", "best"]),
              help="Search order: breadth-first, or best-first by layout cost (docs/exploration.md).")
@TARGET_LENGTH
@click.option("--smooth", default=20, show_default=True, type=int, help="Laplacian smoothing iterations.")
@click.option("--pareto", default="min_scaled_jacobian,edge_groups", show_default=True,
              help="The two metrics of the Pareto front.")
@click.option("--formfind", is_flag=True, help="Also form-find each variant (angle deviation, thrust, rise).")
@click.option("--workers", default=1, show_default=True, type=int, help="Processes evaluating the variants.")
@click.option("--scheduler", default=None, help="Evaluate on the Dask cluster at this address (vaultgram[dask]).")
@input_options
def explore_command(domain_path, out_dir, spacing, rules_dir, limit, depth, seed, order, target_length, smooth,
                    pareto, formfind, workers, scheduler, input_format, layers) -> None:
    """Explore the topology variants of a DOMAIN: a breadth-first or best-first search over the rulebook's choice
    points (choose steps), de-duplicated by layout isomorphism, each variant meshed, measured and ranked.

    Writes state_space.json, variants.json, index.html (the gallery) and variants/vNNN/ (decomposition.json,
    patches.json, mesh.json) to --out; docs/exploration.md.
    """
    from vaultgram.domain import load_domain
    from vaultgram.exploration.explore import ExploreOptions, explore, write_exploration
    from vaultgram.exploration.parallel import check_workers, connect
    from vaultgram.exploration.ranking import parse_pareto
    from vaultgram.exploration.search import check_bounds

    check_bounds(limit, depth)
    check_workers(workers)
    options = ExploreOptions(spacing, rules_dir, limit, depth, seed, target_length, smooth, parse_pareto(pareto),
                             formfind, order)
    domain = load_domain(domain_path, input_format, layer_names(layers), spacing)
    client = connect(scheduler) if scheduler else None
    try:
        exp = explore(domain, options, workers, client)
    finally:
        if client is not None:
            client.close()
    with output_folder(out_dir) as stage:
        write_exploration(exp, stage)
    echo_exploration(exp, Path(out_dir))


def echo_exploration(exp, out: Path) -> None:
    """What the search found, and where the gallery is."""
    counts = exp.result
    if not exp.choice_steps:
        click.echo("the rulebook has no choice points (choose steps): explored one variant")
    elif len(counts.states) == 1:
        click.echo("no choice point offered a choice on this domain: one variant")
    click.echo(f"{len(counts.states)} states visited, {len(counts.variants)} distinct variants "
               f"({counts.hashes} hashed, {counts.exact_checks} exact checks, {counts.collisions} collisions) "
               f"in {counts.seconds:.2f} s; Pareto front: {', '.join(str(v) for v in sorted(exp.front)) or 'none'}")
    click.echo(f"wrote {out / 'index.html'}, {out / 'variants.json'}, {out / 'state_space.json'}")


@main.command("replay")
@click.argument("domain_path", metavar="DOMAIN", type=click.Path(dir_okay=False))
@click.argument("state_space", metavar="STATE_SPACE.json", type=click.Path(dir_okay=False))
@click.option("--variant", required=True, type=int, help="The variant's id (state_space.json, variants.json).")
@OUT
@input_options
def replay_command(domain_path, state_space, variant, out_dir, input_format, layers) -> None:
    """Rebuild one variant that vaultgram explore found, from the DOMAIN: the same decomposition.json,
    patches.json and mesh.json, byte for byte."""
    from vaultgram.domain import load_domain
    from vaultgram.exploration.explore import replay_variant, write_files

    options = read_json(state_space).get("options", {}) if Path(state_space).is_file() else {}
    domain = load_domain(domain_path, input_format, layer_names(layers), options.get("spacing", 0.02))
    ev = replay_variant(domain, state_space, variant)
    with output_folder(out_dir) as stage:
        write_files(ev, stage)
    click.echo(f"variant {variant}: wrote {', '.join(str(Path(out_dir) / n) for n in sorted(ev.files))}")
