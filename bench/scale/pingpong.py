"""Ping-pong between 2 ranks on this machine (mpi4py): the latency and bandwidth of Open MPI's
shared memory, for bench/scale/run's `local` platform (the loopback of the validation runs).
Prints `latency_us bandwidth_gbps`: half the round trip of a 1-byte message, and 2 x 8 MiB over the
round trip of an 8 MiB message (medians of 50 and 20 round trips).

Usage: mpirun -np 2 /usr/bin/python3 bench/scale/pingpong.py
"""
import statistics

import numpy as np
from mpi4py import MPI

comm = MPI.COMM_WORLD
rank = comm.Get_rank()


def round_trips(nbytes, reps):
    buf = np.zeros(nbytes, dtype=np.uint8)
    times = []
    for _ in range(reps + 3):
        comm.Barrier()
        t0 = MPI.Wtime()
        if rank == 0:
            comm.Send(buf, dest=1)
            comm.Recv(buf, source=1)
        else:
            comm.Recv(buf, source=0)
            comm.Send(buf, dest=0)
        times.append(MPI.Wtime() - t0)
    return statistics.median(times[3:])


small = round_trips(1, 50)
big = round_trips(8 << 20, 20)
if rank == 0:
    print(f"{small / 2 * 1e6:.2f} {2 * (8 << 20) * 8 / big / 1e9:.2f}")
