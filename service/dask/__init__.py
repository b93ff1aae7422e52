"""Studies on Dask: the client and cluster (executor), one study's job, the worker's tasks."""
