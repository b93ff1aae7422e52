"""Response bodies of the REST API (they make the OpenAPI schema at ``/openapi.json``)."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, Field

__all__ = [
    "ErrorOut",
    "StudyStatus",
    "StudyList",
    "RunsPage",
    "RunDetail",
    "RunSurface",
    "RunProfile",
    "CompareOut",
    "Deleted",
    "ModelInfo",
    "ModelsOut",
    "BeltsOut",
    "Health",
]

#: ``damaged``: a listed study whose stored ``study.json`` cannot be read (its message names
#: the file and the way out; its counts read 0, its results are on disk as they were).
State = Literal["queued", "running", "done", "failed", "cancelled", "damaged"]


class ErrorOut(BaseModel):
    """Every error: a kind and one line naming the problem (and the field)."""

    error: str = Field(..., description="invalid | not_found | too_large | unauthorized | ...")
    message: str


class StudyStatus(BaseModel):
    id: str
    name: str
    state: State
    total: int = Field(..., description="runs in the study")
    done: int = Field(..., description="runs finished (ok, warning or failed)")
    failed: int = Field(..., description="runs with status failed")
    elapsed_s: float = Field(..., description="compute wall time so far [s]")
    eta_s: float | None = Field(None, description="estimated time left [s]")
    message: str = ""
    created_at: float | None = Field(None, description="Unix time")
    started_at: float | None = None
    finished_at: float | None = None
    dynamics: bool
    grid_points: int | None = Field(None, description="grid points (grid x zip groups)")
    merged: int = Field(0, description="grid points merged into an identical run")
    merged_axes: list[str] = Field(default_factory=list, description=(
        "axes that change no run of the study (their column null in every row), so every "
        "point that differs only in them was merged"))
    axes: dict[str, str] = Field(..., description="axis name -> runs column")
    engine_version: str | None = None
    belt_choices: list[dict[str, Any]] | None = Field(None, description=(
        "the belts belt.type: auto chose, as study.json holds them: one per conveyor design "
        "that chose one, {axes (the design's conveyor axes, {} for one design), type, kind, "
        "passed (false: no catalogue belt passes, the heaviest is used and note is the "
        "warning), mass_kg_m, safety_factor, safety_factor_start, case, next_lighter: {type, "
        "mass_kg_m, safety_factor, safety_factor_start} or null, note}; null when the "
        "conveyor gives its belt"))
    status_url: str
    runs_url: str


class StudyList(BaseModel):
    studies: list[StudyStatus]


class UnreadablePart(BaseModel):
    file: str = Field(..., description="the part file on the service's disk")
    reason: str = Field(..., description="why Arrow cannot read it")


class RunsPage(BaseModel):
    study_id: str
    state: State | None = Field(None, description="the study's state: while it is queued or "
                                "running the rows are those stored so far")
    done: int | None = Field(None, description="the study's runs finished so far")
    study_runs: int | None = Field(None, description="the study's runs in all")
    total: int = Field(..., description="rows matching the filters")
    offset: int
    limit: int | None
    runs: list[dict[str, Any]] = Field(
        ..., description="SPEC section 4 rows; te_components_kn as an object (with columns=: "
        "exactly the columns asked, te_<part>_kn as stored)"
    )
    unreadable_parts: list[UnreadablePart] | None = Field(
        None, description="only when runs part files cannot be read (damaged on disk): each "
        "file and why; their rows are not in runs (a CSV or Parquet download is refused: 500 "
        "naming them)")
    message: str | None = Field(None, description="only with unreadable_parts: what they "
                                "mean and the way out; or, when no row matched, a filter that "
                                "names a study axis stored under another column "
                                "(stop_time_s is stop_time_target_s)")


class AccuracyOut(BaseModel):
    study_id: str
    state: State | None = Field(None, description="the study's state: while it is queued or "
                                "running the table holds the sampled runs stored so far")
    sample: dict[str, Any] | None = Field(
        None, description="the study's accuracy: {sample, seed} (null: none asked)")
    total: int = Field(..., description="sampled runs with error bars so far")
    columns: list[dict[str, Any]] = Field(
        ..., description="the error of each result column over the sample: column, unit, "
        "runs, value_median, err_median, err_max, err_rel_max_pct")
    runs: list[dict[str, Any]] = Field(
        ..., description="the accuracy table: run_id, <figure>_err, <figure>_converged, "
        "accuracy_elements, accuracy_methods")


class RunDetail(BaseModel):
    study_id: str
    run_id: str
    summary: dict[str, Any]
    timeseries: dict[str, list[float | None]] | None = Field(
        None, description="SPEC section 5 key points, column -> values (null without dynamics)"
    )
    accuracy: dict[str, Any] | None = Field(
        None, description="the run's error bars where it is in the study's accuracy sample: "
        "<figure>_err, <figure>_converged, accuracy_elements, accuracy_methods (null for a "
        "run outside the sample)"
    )


class RunSurface(BaseModel):
    study_id: str
    run_id: str
    source: Literal["stored", "recomputed"] = Field(
        ..., description="stored (a study with surface: true) or recomputed from the run's "
        "inputs (runs are deterministic)"
    )
    rows: int = Field(..., description="rows of the long table (sampled times x springs)")
    surface: dict[str, list[float | None]] | None = Field(
        None, description="column -> values: t_s, s_m, tension_kn, velocity_m_s (null "
        "without a transient)"
    )
    reason: str | None = Field(
        None, description="why there are no rows (a steady-only study, a failed run); absent "
        "when there are rows"
    )


class RunProfile(BaseModel):
    study_id: str
    run_id: str
    source: Literal["stored", "recomputed"] = Field(
        ..., description="stored with the run, or recomputed from the run's inputs (a run "
        "stored before profiles were)"
    )
    rows: int = Field(..., description="rows: one per element end round the loop")
    profile: dict[str, list[float | str | None]] | None = Field(
        None, description="column -> values: s_m, strand, elevation_m, tension_kn, sag_pct "
        "(null for a run that raised)"
    )


class CompareOut(BaseModel):
    study_id: str
    baseline: str
    candidate: str
    metrics: list[str]
    pairs: list[dict[str, Any]] = Field(
        ..., description="axes, run ids and <metric>_baseline/_candidate/_ratio"
    )
    failed_pairs: int = Field(0, description="pairs with a failed run (no ratio)")
    summary: dict[str, Any] = Field(
        ..., description="metric -> {overall: stats, by_axis: {axis: {value: stats}}}"
    )
    state: str | None = Field(
        None, description="the study's state: a running study answers with the pairs so far"
    )
    same_in_all_pairs: dict[str, Any] = Field(
        default_factory=dict, description="axes with one value in every pair (not listed per "
        "pair): no difference between the two models' runs")
    ratio: str = Field("", description="how the ratios are formed (magnitudes, sign column)")
    done: int | None = Field(None, description="runs finished so far")
    total: int | None = Field(None, description="runs of the study")


class Deleted(BaseModel):
    id: str
    state: Literal["deleted"]
    deleted: bool
    cancelled: bool = Field(description="the study was still queued or running: its tasks "
                            "were cancelled")
    was: str = Field(description="the study's state before it was deleted")


class ParamInfo(BaseModel):
    name: str
    default: float | None
    doc: str
    max: float | None = Field(None, description="the largest value taken (null: no bound "
                              "beyond the model's own checks)")


class ModelInfo(BaseModel):
    name: str
    description: str
    aliases: list[str]
    parameters: list[ParamInfo]


class ModelsOut(BaseModel):
    models: list[ModelInfo]


class BeltsOut(BaseModel):
    belts: list[dict[str, Any]]


class Health(BaseModel):
    status: Literal["ok"]
    version: str
    executor: dict[str, Any]
    studies_running: int
