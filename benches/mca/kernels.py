#!/usr/bin/env python3
"""llvm-mca over the AVX-512 batch loops of a built binary: issue 14's scheduling model.

    cargo build --release -p brdf-tools --bin peer_roughconductor
    python3 benches/mca/kernels.py target/release/peer_roughconductor

For every instantiation of `brdf::batch::kernel_avx512` in BINARY it finds the 16-lane loop
(the largest backward-branch region whose instructions are mostly zmm ones), prints its
counts of 16-lane square roots, divisions and estimates, and runs llvm-mca on it for each
CPU: predicted cycles per iteration (16 evaluations), the busiest resource, and
M evaluations/s per GHz. For Intel it adds a hand-made bound that llvm-mca's models lack
(see the README, Performance): max(divider, ports) with the divider busy 12 cycles per zmm
`vsqrtps` and 10 per zmm `vdivps`, and the 512-bit uops of the sapphirerapids model spread
over ports 0 and 5. Every figure printed is a model, not a measurement.

Needs binutils (nm, objdump) and an llvm-mca with the znver4 and sapphirerapids models
(LLVM >= 17; Debian: `apt-get install llvm-19`). Options: --mca PATH, --cpus a,b,c,
--dump DIR (writes each loop as DIR/kernel-ADDR.s for llvm-mca by hand).
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys

SQRT_CYCLES, DIV_CYCLES = 12, 10  # Intel divider occupancy per zmm vsqrtps / vdivps


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True, check=True).stdout


def find_mca(given):
    if given:
        return given
    for v in range(25, 16, -1):
        for p in [shutil.which('llvm-mca-%d' % v), '/usr/lib/llvm-%d/bin/llvm-mca' % v]:
            if p and os.path.exists(p):
                return p
    sys.exit('kernels.py: no llvm-mca >= 17 found (Debian: apt-get install llvm-19)')


def kernels(binary):
    """(address, size) of every kernel_avx512 instantiation (the one-lane-model kernel and
    the explicit-lane kernel `kernel_avx512_lanes16`)."""
    out = []
    for line in run(['nm', '-S', '-C', binary]).splitlines():
        f = line.split(maxsplit=3)
        if len(f) == 4 and f[2] in 'tT' and f[3] in ('brdf::batch::kernel_avx512', 'brdf::batch::kernel_avx512_lanes16'):
            out.append((int(f[0], 16), int(f[1], 16)))
    return sorted(out)


def hot_loop(binary, addr, size):
    """The instructions (AT&T text) of the kernel's 16-lane loop, branch targets relabelled."""
    dis = run(['objdump', '-d', '--no-show-raw-insn', '-M', 'att',
               '--start-address=%#x' % addr, '--stop-address=%#x' % (addr + size), binary])
    ins = []
    for line in dis.splitlines():
        m = re.match(r'\s*([0-9a-f]+):\s+(\S.*)', line)
        if m:
            ins.append((int(m.group(1), 16), re.sub(r'\s*#.*$', '', m.group(2)).strip()))
    best = None
    for a, text in ins:
        m = re.match(r'j\w+\s+([0-9a-f]+)\b', text)
        if m and int(m.group(1), 16) <= a:
            region = [t for b, t in ins if int(m.group(1), 16) <= b <= a]
            zmm = sum('%zmm' in t for t in region)
            if len(region) >= 40 and zmm >= 0.7 * len(region):
                if best is None or len(region) > len(best):
                    best = region
    if best is None:
        return None
    return [re.sub(r'^(j\w+|call)\s+[0-9a-f]+\b.*$', r'\1 .Lloop', t) for t in best]


def mca(tool, cpu, asm):
    """(cycles per iteration, {resource: pressure per iteration})."""
    r = subprocess.run([tool, '-mtriple=x86_64', '-mcpu=' + cpu, '-iterations=300'],
                       input='.Lloop:\n' + '\n'.join(asm) + '\n', capture_output=True, text=True)
    if r.returncode != 0:
        return None, {r.stderr.strip().splitlines()[-1][:60]: 0.0}
    out = r.stdout
    cycles = int(re.search(r'Total Cycles:\s+(\d+)', out).group(1)) / 300
    names = re.findall(r'^\[([\d.]+)\]\s+- (\S+)', out, re.M)
    lines = out.split('Resource pressure per iteration:')[1].strip().splitlines()
    values = [0.0 if v == '-' else float(v) for v in lines[1].split()]
    return cycles, {n: v for (_, n), v in zip(names, values)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('binary')
    ap.add_argument('--mca')
    ap.add_argument('--cpus', default='znver4,sapphirerapids,icelake-server')
    ap.add_argument('--dump')
    a = ap.parse_args()
    tool = find_mca(a.mca)
    version = re.search(r'LLVM version \S+', run([tool, '--version']))
    print('%s (%s): every figure below is an llvm-mca model, not a measurement' %
          (tool, version.group(0) if version else 'unknown version'))
    for addr, size in kernels(a.binary):
        asm = hot_loop(a.binary, addr, size)
        if asm is None:
            continue
        n = {k: sum(t.startswith(k + ' ') and '%zmm' in t for t in asm)
             for k in ['vsqrtps', 'vdivps', 'vrsqrt14ps', 'vrcp14ps']}
        print('\nkernel_avx512 @ %#x: %d instructions; zmm %s' % (
            addr, len(asm), ', '.join('%s %d' % kv for kv in n.items())))
        if a.dump:
            os.makedirs(a.dump, exist_ok=True)
            with open(os.path.join(a.dump, 'kernel-%x.s' % addr), 'w') as f:
                f.write('.Lloop:\n' + '\n'.join(asm) + '\n')
        for cpu in a.cpus.split(','):
            cycles, p = mca(tool, cpu, asm)
            if cycles is None:
                print('  %-16s %s' % (cpu, next(iter(p))))
                continue
            top = max(p, key=p.get)
            print('  %-16s %6.1f cycles/iteration  %5.1f M/s per GHz  busiest %s %.1f' % (
                cpu, cycles, 16e3 / cycles, top, p[top]))
            if 'SPRPort00' in p:  # LLVM 14 maps sapphirerapids to its Skylake-server model
                ports = (p.get('SPRPort00', 0) + p.get('SPRPort05', 0)) / 2
                div = SQRT_CYCLES * n['vsqrtps'] + DIV_CYCLES * n['vdivps']
                print('  %-16s %6.1f cycles/iteration  %5.1f M/s per GHz  (divider %d, '
                      'ports 0+5 %.1f)' % ('spr bound', max(ports, div),
                                          16e3 / max(ports, div), div, ports))


if __name__ == '__main__':
    main()
