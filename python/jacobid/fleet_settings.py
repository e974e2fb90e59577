# SPDX-License-Identifier: MIT
"""jacobid.fleet's worker settings (:func:`jacobid.fleet.worker_settings`) for workers that jacobid does not start.

A nanny that imports this module before it reads its configuration spawns its worker with them:

    dask worker tcp://hostA:8786 --nworkers auto --nthreads 1 --preload-nanny jacobid.fleet_settings

Dask's environment variables cannot do it: a DASK_* value for a dict is merged into Dask's default, so it can add
to ``distributed.nanny.pre-spawn-environ`` but not remove its MALLOC_TRIM_THRESHOLD_ (docs/fleet.md,
"Worker settings"). The nanny imports its preloads before it reads the settings, and this module changes the
configuration of the nanny's process for good: import it only in a process that exists to run workers.
"""
import dask

from jacobid.fleet import worker_settings

dask.config.set(worker_settings())
