"""<stage>_chunk: the part of one chunk job of a chunked stage (its items start..stop), one
part file for the stage's gather job (vines.pipeline.parts)."""
from collections.abc import Mapping

from vines.pipeline import stages
from vines.pipeline.jobs import run_job
from vines.pipeline.parts import write_part

sm = snakemake  # noqa: F821  (injected by Snakemake)

#: params that are not keywords of the part function
NOT_KEYWORDS = ("part", "code", "script", "args")


def main():
    stage = sm.rule.removesuffix("_chunk")
    start, stop = sm.params.part
    kw = {k: dict(v) if isinstance(v, Mapping) else v for k, v in sm.params.items()
          if k not in NOT_KEYWORDS}
    print(f"{stage} {sm.wildcards.name}, chunk {sm.wildcards.k}: items {start}..{stop - 1}, "
          f"{sm.threads} threads", flush=True)
    part = getattr(stages, f"{stage}_part")(*sm.params.args, **kw, start=start, stop=stop,
                                            n_workers=sm.threads)
    write_part(part, sm.output[0])
    print("done", flush=True)


run_job(sm, main)
