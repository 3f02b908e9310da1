"""Python client of the tribosim service (``tribosim serve``): ball-on-disc tribocorrosion
runs after Dalmau et al., Wear 394-395 (2018), from a notebook.

    import tribosim
    client = tribosim.Client()                  # TRIBOSIM_URL, TRIBOSIM_TOKEN
    job = client.jobs.submit({"test": {"cycles": 300}})
    job.wait()                                   # a progress bar over the cycles
    result = job.result()
    result.cycles                                # a DataFrame, units in the column names

The HTTP client is httpx (one synchronous API for plain calls and for reading the job's
event stream as it arrives); pandas and numpy come with the ``pandas`` extra, tqdm's
progress bar with ``progress``. docs/notebook.md in the repository walks through it.
"""

from .calibrations import Calibration, Calibrations, Estimate, Fit
from .client import Client
from .errors import (
    ApiError,
    AuthError,
    ConflictError,
    FieldError,
    NotFoundError,
    RateLimitedError,
    RefusedError,
    RunFailedError,
    ServerError,
    TransportError,
    TribosimError,
    ValidationError,
    WaitTimeoutError,
)
from .events import CycleEvent, Event, StatusEvent
from .jobs import Job, Jobs
from .measurements import Measurements
from .records import CalibrationInfo, JobInfo, Preset, StudyInfo, Surface
from .result import Model, PressureMap, Result, WearMap
from .studies import Studies, Study
from .surfaces import Surfaces

__version__ = "0.1.0"

__all__ = [
    "ApiError",
    "AuthError",
    "Calibration",
    "CalibrationInfo",
    "Calibrations",
    "Client",
    "ConflictError",
    "CycleEvent",
    "Estimate",
    "Event",
    "FieldError",
    "Fit",
    "Job",
    "JobInfo",
    "Jobs",
    "Measurements",
    "Model",
    "NotFoundError",
    "Preset",
    "PressureMap",
    "RateLimitedError",
    "RefusedError",
    "Result",
    "RunFailedError",
    "ServerError",
    "StatusEvent",
    "Studies",
    "Study",
    "StudyInfo",
    "Surface",
    "Surfaces",
    "TransportError",
    "TribosimError",
    "ValidationError",
    "WaitTimeoutError",
    "WearMap",
]
