"""Writes a SimGrid platform file (and an smpirun hostfile) for the SMPI build's runs (docs/smpi.md).

    python3 scripts/scale_platform.py KIND HOSTS OUT.xml [--hostfile OUT.txt]
                                      [--loopback-gbps G --loopback-us U --cores C]

KIND:
  fattree   2-level fat tree with full bisection: HOSTS = d1 * d2 hosts, d1 per leaf switch, every
            leaf switch cabled once to each of d1 core switches; every link 100 Gbit/s, 1 us,
            full duplex (an EDR InfiniBand class of cluster).
  torus     3-D torus of HOSTS nodes (dimensions as even as HOSTS's factors allow), links
            425 MB/s (3.4 Gbit/s) and 1 us per hop, full duplex (Blue Gene/P's torus links, the
            anchor's machine).
  ethernet  a PC cluster on 10 Gbit/s Ethernet: one 10 Gbit/s, 20 us full-duplex link per host into
            one non-blocking switch (a backbone that limits no flow), as in the first paper's era of
            commodity clusters.
  local     this machine, for validating against real runs: one host with --cores cores; ranks
            talk through its loopback (--loopback-gbps, --loopback-us: measured shared-memory MPI
            bandwidth and latency).
Every host computes at 1 Gflop/s: the SMPI build charges one flop per nanosecond that the
kernels take on the core the rates were measured on (bench/scale/pixel_rates.h), so a host is
that core. HOSTS must be >= 1 (fattree: a product d1 * d2 with d1, d2 >= 2 is chosen).
"""
import argparse
import sys


def factor3(n):
    """Three factors of n, as equal as possible, largest first."""
    best = None
    for a in range(1, n + 1):
        if n % a:
            continue
        for b in range(1, n // a + 1):
            if (n // a) % b:
                continue
            c = n // a // b
            dims = sorted((a, b, c), reverse=True)
            if best is None or dims[0] - dims[2] < best[0] - best[2]:
                best = dims
    return best


def fat_tree_split(n):
    """n = d1 * d2 with d1 >= d2 as close as possible (d1 hosts per leaf, d2 leaves)."""
    d2 = max(d for d in range(1, int(n ** 0.5) + 1) if n % d == 0)
    return n // d2, d2


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=["fattree", "torus", "ethernet", "local"])
    ap.add_argument("hosts", type=int)
    ap.add_argument("out")
    ap.add_argument("--hostfile")
    ap.add_argument("--loopback-gbps", type=float, default=40.0)
    ap.add_argument("--loopback-us", type=float, default=1.0)
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--print-network", action="store_true",
                    help="print LATENCY_US,GBIT_PER_S,RANKS_PER_CORE: the platform as the cost model of "
                         "compositing.strategy auto sees it (bench_scale --network, forecast_sweep)")
    a = ap.parse_args()
    if a.hosts < 1:
        sys.exit("scale_platform: HOSTS must be >= 1")
    n = a.hosts
    common = 'prefix="node-" suffix="" speed="1Gf"'
    if a.kind == "fattree":
        d1, d2 = fat_tree_split(n)
        if d2 < 2:
            sys.exit(f"scale_platform: a 2-level fat tree needs HOSTS = d1 * d2 with d1, d2 >= 2, not {n}")
        cluster = (f'<cluster id="fattree" {common} radical="0-{n - 1}" bw="100Gbps" lat="1us" '
                   f'sharing_policy="SPLITDUPLEX" topology="FAT_TREE" '
                   f'topo_parameters="2;{d1},{d2};1,{d1};1,1"/>')
        note = f"2-level fat tree: {d2} leaf switches of {d1} hosts, {d1} core switches, 100 Gbit/s, 1 us"
    elif a.kind == "torus":
        dims = factor3(n)
        cluster = (f'<cluster id="torus" {common} radical="0-{n - 1}" bw="425MBps" lat="1us" '
                   f'sharing_policy="SPLITDUPLEX" topology="TORUS" '
                   f'topo_parameters="{",".join(map(str, dims))}"/>')
        note = f"3-D torus {'x'.join(map(str, dims))}, 425 MB/s and 1 us per link"
    elif a.kind == "ethernet":
        cluster = (f'<cluster id="ethernet" {common} radical="0-{n - 1}" bw="10Gbps" lat="20us" '
                   f'sharing_policy="SPLITDUPLEX" bb_bw="10Gbps" bb_lat="0us" bb_sharing_policy="FATPIPE"/>')
        note = "10 Gbit/s Ethernet, 20 us, one non-blocking switch"
    else:
        cluster = (f'<cluster id="local" {common} radical="0-0" core="{a.cores}" bw="100Gbps" lat="0us" '
                   f'loopback_bw="{a.loopback_gbps}Gbps" loopback_lat="{a.loopback_us}us"/>')
        note = (f"this machine: 1 host, {a.cores} cores, loopback {a.loopback_gbps} Gbit/s, "
                f"{a.loopback_us} us")
    with open(a.out, "w") as f:
        f.write("<?xml version='1.0'?>\n"
                '<!DOCTYPE platform SYSTEM "https://simgrid.org/simgrid.dtd">\n'
                f'<!-- {note}; written by scripts/scale_platform.py -->\n'
                '<platform version="4.1">\n'
                '  <zone id="world" routing="Full">\n'
                f'    {cluster}\n'
                '  </zone>\n'
                '</platform>\n')
    if a.hostfile:
        with open(a.hostfile, "w") as f:
            hosts = ["node-0"] * n if a.kind == "local" else [f"node-{i}" for i in range(n)]
            f.write("\n".join(hosts) + "\n")
    if a.print_network:
        print(model_network(a))


def model_network(a):
    """One message's latency end to end (us), one host's link (Gbit/s), ranks per core."""
    n = a.hosts
    if a.kind == "fattree":  # up to 4 links of 1 us on a route (host, leaf, core, leaf, host)
        return f"4,100,1"
    if a.kind == "torus":  # 1 us per hop, the mean ring distance n_i / 4 along each axis
        return f"{1 + sum(d / 4 for d in factor3(n)):g},3.4,1"
    if a.kind == "ethernet":  # 20 us to the switch and 20 from it
        return "40,10,1"
    return f"{a.loopback_us:g},{a.loopback_gbps:g},{max(1.0, n / a.cores):g}"


main()
