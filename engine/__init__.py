"""beltstudy engine: conveyor models, friction models, statics and transient dynamics."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("beltstudy")
except PackageNotFoundError:  # pragma: no cover - running from a source tree without install
    __version__ = "0.4.1"
