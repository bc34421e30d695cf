"""Parameter sets: the current model's table, the history, proposals, YAML in and out.

Fits and diagnoses arrive here as proposals: their numbers beside the current ones and
the gap before/after, to accept or discard. Every set the user had — the start, accepted
proposals, loaded files, their own edits — stays in the history, to compare and restore.
"""

from __future__ import annotations

import viser

from ...identify.paramfile import params_to_yaml
from ...model import FrictionParams, default_params
from ...model.errors import FrictionError, ParameterError
from .. import plots
from .context import Context, Proposal
from .fields import fields_of, get_value
from .session import Entry


def _fields_of(*ps: FrictionParams):
    """The union of the fields of several sets (they may have different numbers of knots)."""
    seen, out = set(), []
    for p in ps:
        for f in fields_of(p):
            if f.path not in seen:
                seen.add(f.path)
                out.append(f)
    return out


def _cell(p: FrictionParams, path: str) -> str:
    v = get_value(p, path)
    if v is None:
        return "—"
    s = f"{v:.5g}"
    u = p.uncertainty.get(path)
    return f"{s} ± {u:.2g}" if u else s


def params_table(p: FrictionParams) -> str:
    """The current model, every field with its unit and ±1σ where an estimate carries one."""
    rows = [f"**Current model** ({p.model})", "", "| parameter | value | unit |", "|---|---|---|"]
    for f in _fields_of(p):
        if get_value(p, f.path) is None:
            continue
        rows.append(f"| {f.label} | {_cell(p, f.path)} | {f.unit} |")
    if p.effects:
        rows.append("")
        rows.append("Effects: " + ", ".join(e.get("name", "?") for e in p.effects))
    return "\n".join(rows)


def compare_table(a: FrictionParams, b: FrictionParams, name_a: str, name_b: str, only_changed: bool = True) -> str:
    rows = [f"| parameter | {name_a} | {name_b} | unit |", "|---|---|---|---|"]
    unit_a = {f.path: f.unit for f in fields_of(a)}
    unit_b = {f.path: f.unit for f in fields_of(b)}
    for f in _fields_of(a, b):
        va, vb = get_value(a, f.path), get_value(b, f.path)
        if only_changed and va is not None and vb is not None and abs(va - vb) <= 1e-12 * max(abs(va), abs(vb), 1e-300):
            continue
        if va is None and vb is None:
            continue
        ua, ub = unit_a.get(f.path, f.unit), unit_b.get(f.path, f.unit)
        rows.append(f"| {f.label} | {_cell(a, f.path)} | **{_cell(b, f.path)}** | {ub if ua == ub else f'{ua} → {ub}'} |")
    ea = ", ".join(e.get("name", "?") for e in a.effects) or "none"
    eb = ", ".join(e.get("name", "?") for e in b.effects) or "none"
    if ea != eb:
        rows.append(f"| effects | {ea} | **{eb}** | |")
    return "\n".join(rows) if len(rows) > 2 else "(no parameter differs)"


def params_from_yaml(content: bytes, name: str) -> FrictionParams:
    """An uploaded parameter file, read and checked exactly as the command line reads one
    (``identify.paramfile``: size and knot limits, an empty file, values YAML cannot build)."""
    from ...identify.paramfile import params_from_yaml as parse

    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise ParameterError(f"{name}: not a UTF-8 text file (byte {e.start})") from None
    return parse(text, name)


class SetsTab:
    def __init__(self, ctx: Context, gui: viser.GuiApi, start_label: str):
        self.ctx = ctx
        self.gui = gui
        self._shown = None
        s = ctx.session
        if not s.history:
            s.add(start_label, s.params)

        # ---------------------------------------------------------------- proposal (left, top)
        self.gui_proposal = gui.add_folder("Proposal", visible=False, order=1.0)
        with self.gui_proposal:
            # what it is and its gap, then the buttons, then its details and numbers: a fit's table
            # of every parameter had put Accept two screens down at 1280×720
            self.gui_prop_head = gui.add_markdown("")
            self.gui_accept = gui.add_button("Accept", color="green", hint="make the proposal the current model")
            self.gui_discard = gui.add_button("Discard", hint="keep the current model")
            self.gui_prop_text = gui.add_markdown("")

    def add_view(self, panel) -> None:
        """The Parameter sets tab (right) and the Files folder (left)."""
        ctx, gui, s = self.ctx, self.gui, self.ctx.session

        # ---------------------------------------------------------------- view (right)
        with panel.add_tab("Parameter sets"):
            self.gui_table = gui.add_markdown(params_table(s.params))
            gui.add_markdown("**History** — every parameter set of this session")
            self.gui_pick = gui.add_dropdown("set", self._titles(), initial_value=self._titles()[-1])
            self.gui_restore = gui.add_button("Restore this set", hint="make it the current model (the current one stays in the history)")
            self.gui_compare = gui.add_markdown("")

        # ---------------------------------------------------------------- files (left)
        with gui.add_folder("Files", order=9.0):
            self.gui_load = gui.add_upload_button("Load parameter YAML", icon=viser.Icon.FILE_UPLOAD,
                                                  mime_type=".yaml,.yml,text/yaml,application/x-yaml")
            self.gui_export = gui.add_button("Export YAML", icon=viser.Icon.DOWNLOAD)
            self.gui_fresh = gui.add_button("Start from the paper's defaults")

        # ---------------------------------------------------------------- callbacks
        @self.gui_accept.on_click
        def _(_) -> None:
            prop = ctx.proposal
            if prop is None:
                return
            self._remember_edits()
            ctx.session.add(prop.label, prop.params)
            ctx.proposal = None
            self.gui_proposal.visible = False
            ctx.set_params(prop.params, "accepted")
            ctx.status(f"Accepted: {prop.label}.")

        @self.gui_discard.on_click
        def _(_) -> None:
            prop = ctx.proposal
            ctx.proposal = None
            self.gui_proposal.visible = False
            ctx.status(f"Discarded: {prop.label if prop else 'proposal'}.")
            ctx.changed("proposal")

        @self.gui_pick.on_update
        def _(_) -> None:
            self._show_compare()

        @self.gui_restore.on_click
        def _(_) -> None:
            e = self._picked()
            if e is None:
                return
            self._remember_edits()
            ctx.session.add(f"restored {e.label}", e.params)
            ctx.set_params(e.params, "restored")
            ctx.status(f"Restored: {e.label}.")

        @self.gui_load.on_upload
        def _(event) -> None:
            f = self.gui_load.value
            try:
                p = params_from_yaml(f.content, f.name)
            except FrictionError as e:
                ctx.status(f"⚠ {e}")
                ctx.notify("Cannot load the parameter file", str(e), "red", 10.0)
                return
            self._remember_edits()
            ctx.session.add(f"loaded {f.name}", p)
            ctx.set_params(p, "loaded")
            # a file in the paper's units may leave σ1 and the inertia out: said, since the
            # built-in values are another machine's (a spindle's 0.004 kg·m² became 5, unsaid)
            left = ", ".join(f"{k} {getattr(p, k):g}" for k in p.defaulted)
            ctx.status(f"Loaded **{f.name}**." + (f" ⚠ It does not give {' or '.join(p.defaulted)}: the built-in "
                                                  f"defaults are used ({left}), not this machine's (a fit started "
                                                  f"from it takes them as unknown)" if left else ""))

        @self.gui_export.on_click
        def _(event) -> None:
            try:
                text = params_to_yaml(ctx.params.validate())
            except ParameterError as e:
                ctx.status(f"⚠ cannot export: {e}")
                return
            event.client.send_file_download("leuven_friction_params.yaml", text.encode(), save_immediately=True)

        @self.gui_fresh.on_click
        def _(_) -> None:
            self._remember_edits()
            p = default_params()
            ctx.session.add("paper defaults", p)
            ctx.set_params(p, "restored")

        ctx.listeners.append(self._on_change)

    # ------------------------------------------------------------------
    def _titles(self) -> tuple:
        return tuple(e.title(i) for i, e in enumerate(self.ctx.session.history))

    def _picked(self) -> Entry | None:
        titles = self._titles()
        if self.gui_pick.value in titles:
            return self.ctx.session.history[titles.index(self.gui_pick.value)]
        return None

    def _remember_edits(self) -> None:
        """Before the current model is replaced: keep the user's edits as a set of their own."""
        h = self.ctx.session.history
        if not h or h[-1].params.to_dict() != self.ctx.params.to_dict():
            self.ctx.session.add("your edits", self.ctx.params)

    def _show_compare(self) -> None:
        e = self._picked()
        if e is not None:
            self.gui_compare.content = compare_table(self.ctx.params, e.params, "current", e.label)

    def refresh(self) -> None:
        """Bring the table and the comparison up to the current model (called by the page's
        background loop a few times a second, so slider moves do not wait for it)."""
        if self._shown is not self.ctx.params:
            self._shown = self.ctx.params
            self.gui_table.content = params_table(self._shown)
            self._show_compare()

    def _on_change(self, reason: str) -> None:
        if reason == "edit":
            return  # refresh() follows within a fraction of a second
        self._shown = self.ctx.params
        self.gui_table.content = params_table(self.ctx.params)
        if reason in ("accepted", "restored", "loaded", "proposal"):
            titles = self._titles()
            self.gui_pick.options = titles
            self.gui_pick.value = titles[-1]
        self._show_compare()

    def propose(self, prop: Proposal) -> None:
        ctx = self.ctx
        ctx.proposal = prop
        gap = ""
        if prop.gap_before is not None and prop.gap_after is not None:
            u = plots.shown_unit(str(prop.params.units.get("force", "")))
            gap = (f"\n\n**Gap** (RMS measured − model): {prop.gap_before:.4g} {u} now → "
                   f"**{prop.gap_after:.4g} {u}** with the proposal")
            if prop.gap_after > prop.gap_before:
                # a fit can be worse along the whole record than a set tuned to it (a fit's S(v)
                # and curve come from the levels and branches alone): said before it is accepted
                gap += (f"\n\n⚠ The proposal leaves a larger gap along this recording than the current set "
                        f"({prop.gap_after / prop.gap_before:.2g}×): look at the plots before accepting it.")
        self.gui_prop_head.content = f"**{prop.label}**{gap}"
        self.gui_prop_text.content = f"{prop.text}\n\n" + compare_table(ctx.params, prop.params, "current", "proposed")
        self.gui_proposal.visible = True
        ctx.changed("proposal")
        ctx.notify("Proposal ready", f"{prop.label}: accept or discard it (left panel).", "green", 5.0)
