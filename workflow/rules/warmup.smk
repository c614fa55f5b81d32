# Compile the numba kernels once, before the first job (not once in every job that starts
# before the cache exists): vines.pipeline.warmup, a no-op while the cache is warm for these
# sources. Runs only when jobs run (not with -n); a failure leaves the compiling to the jobs.
import json
import subprocess


onstart:
    subprocess.run(
        [
            sys.executable,
            "-m",
            "vines.pipeline.warmup",
            "--model",
            json.dumps(MODEL),
            "--simulation",
            json.dumps(SIMULATION),
            "--jobs",
            str(workflow.resource_settings.cores or 1),
        ],
        check=False,
    )
