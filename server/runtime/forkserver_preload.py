"""Imported once by the heavy processes' forkserver before it forks any of them (multiprocessing's forkserver
preload, heavy._current_pool): the compiled kernels are loaded here (warm_up), so every heavy process the
forkserver forks starts with them and with the lanes' modules already imported, sharing their memory with the
forkserver until it writes to it. Each heavy process loaded them itself before: about 2.5 CPU-s and its own
copy of them each, on every start of a server. Imported last, after the lanes' modules: what the
forkserver holds then is frozen out of the garbage collector's reach (gc.freeze), so that a collection in a heavy
process neither walks it nor writes to its pages."""
import gc

from ..core.warm_up import warm_up

warm_up()
gc.collect()
gc.freeze()
