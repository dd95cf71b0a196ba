#!/usr/bin/env bash
# Peer benchmark (issue 14): Mitsuba 3's `roughconductor` BSDF against this crate's batch path
# on the same direction pairs, one thread each. Runs from a fresh clone:
#
#   bash benches/peers/run.sh [N] [--sample]
#
#   N         direction pairs (default 65536), drawn with a fixed seed
#   --sample  also time sampling: Mitsuba's `bsdf.sample` and the crate's `batch::sample`
#             (visible normals as Mitsuba, and the crate's default spherical caps) on the same
#             viewer directions and uniforms; each side's density and weight are checked
#             against an f64 reference at its own directions, and the mean weights against
#             each other (within 4 standard errors)
#
# Environment: PEERS_REPS (timed repetitions, default: about 2^27 evaluations in all),
# PEERS_WARMUP (untimed calls first, default 20), PEERS_PYTHON (interpreter for the venv,
# default python3), DRJIT_LIBLLVM_PATH (an LLVM ≥ 17 shared library; else found or installed).
#
# Steps: a virtual environment in target/peers-venv with pinned Mitsuba and Dr.Jit; the LLVM
# shared library Dr.Jit's LLVM backend loads (Debian's libllvm19, installed with apt-get if
# missing: LLVM 15 and 16 fail with "Cannot select fmaximum"); the pairs file; Mitsuba's
# `eval` (variant llvm_ad_rgb, one Dr.Jit thread, JIT compilation excluded); the crate's
# `batch::eval` (tools/src/bin/peer_roughconductor.rs, built in release mode here); the
# values compared (max relative error ≤ 1e-5, else exit 1); the throughputs printed.
set -euo pipefail

MITSUBA_VERSION=3.9.1
DRJIT_VERSION=1.5.0 # the version mitsuba 3.9.1 requires
NUMPY_VERSION=2.4.6
VARIANT=llvm_ad_rgb
ALPHA=0.3
TOLERANCE=1e-5

N=65536
SAMPLE=0
for arg in "$@"; do
    case "$arg" in
    --sample) SAMPLE=1 ;;
    --help | -h)
        sed -n '2,20p' "$0"
        exit 0
        ;;
    *[!0-9]* | '') echo "run.sh: unknown argument '$arg' (see --help)" >&2 && exit 2 ;;
    *) N=$arg ;;
    esac
done
[ "$N" -ge 1 ] || { echo "run.sh: N must be at least 1" >&2 && exit 2; }
REPS=${PEERS_REPS:-$(((1 << 27) / N > 20 ? (1 << 27) / N : 20))}
WARMUP=${PEERS_WARMUP:-20}

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$ROOT"
TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
VENV=$TARGET/peers-venv
WORK=$TARGET/peers
mkdir -p "$WORK"
PEERS="$ROOT/benches/peers/peers.py"

# --- 1. Python environment with the pinned Mitsuba -------------------------------------------
py=$VENV/bin/python
if ! "$py" -c "import mitsuba, drjit, numpy, sys
sys.exit(not (mitsuba.__version__ == '$MITSUBA_VERSION' and drjit.__version__ == '$DRJIT_VERSION'
              and numpy.__version__ == '$NUMPY_VERSION'))" 2>/dev/null; then
    echo "== creating $VENV (mitsuba==$MITSUBA_VERSION drjit==$DRJIT_VERSION numpy==$NUMPY_VERSION)"
    if ! "${PEERS_PYTHON:-python3}" -m venv --clear "$VENV"; then
        # Debian's python3 ships venv's pip bootstrap separately.
        command -v apt-get >/dev/null || { echo "run.sh: python3 -m venv failed" >&2 && exit 1; }
        SUDO=""
        [ "$(id -u)" -eq 0 ] || SUDO=sudo
        $SUDO apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq python3-venv >/dev/null
        "${PEERS_PYTHON:-python3}" -m venv --clear "$VENV"
    fi
    "$VENV/bin/pip" install --quiet --disable-pip-version-check \
        "mitsuba==$MITSUBA_VERSION" "drjit==$DRJIT_VERSION" "numpy==$NUMPY_VERSION"
fi

# --- 2. The LLVM shared library for Dr.Jit's LLVM backend ------------------------------------
llvm_major() { # the major version in a libLLVM file name, 0 if none
    local v
    v=$(basename "$1" | sed -n 's/^libLLVM[-.]\([0-9][0-9]*\).*/\1/p; s/^libLLVM\.so\.\([0-9][0-9]*\).*/\1/p' | head -n1)
    echo "${v:-0}"
}
find_llvm() { # the newest libLLVM ≥ 17 in the usual places
    local best="" best_v=0 f v
    for f in /usr/lib/x86_64-linux-gnu/libLLVM*.so* /usr/lib/llvm-*/lib/libLLVM*.so* \
        /usr/lib64/libLLVM*.so* /usr/local/lib/libLLVM*.so*; do
        [ -e "$f" ] || continue
        v=$(llvm_major "$f")
        if [ "$v" -ge 17 ] && [ "$v" -gt "$best_v" ]; then best=$f best_v=$v; fi
    done
    echo "$best"
}
if [ -z "${DRJIT_LIBLLVM_PATH:-}" ]; then
    DRJIT_LIBLLVM_PATH=$(find_llvm)
    if [ -z "$DRJIT_LIBLLVM_PATH" ]; then
        echo "== no LLVM >= 17 shared library found: installing Debian's libllvm19"
        if ! command -v apt-get >/dev/null; then
            echo "run.sh: no apt-get: install LLVM >= 17 and set DRJIT_LIBLLVM_PATH" >&2
            exit 1
        fi
        SUDO=""
        [ "$(id -u)" -eq 0 ] || SUDO=sudo
        $SUDO apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq libllvm19 >/dev/null
        DRJIT_LIBLLVM_PATH=$(find_llvm)
        [ -n "$DRJIT_LIBLLVM_PATH" ] || { echo "run.sh: libllvm19 installed but not found" >&2 && exit 1; }
    fi
fi
export DRJIT_LIBLLVM_PATH
LLVM_VERSION=$(dpkg-query -W -f='${Package} ${Version}' "$(dpkg -S "$(readlink -f "$DRJIT_LIBLLVM_PATH")" 2>/dev/null | cut -d: -f1 | head -n1)" 2>/dev/null || true)
LLVM_VERSION=${LLVM_VERSION:-$(basename "$DRJIT_LIBLLVM_PATH")}

# --- 3. The crate's program, release mode ----------------------------------------------------
echo "== building peer_roughconductor (release)"
nice cargo build --quiet --release -p brdf-tools --bin peer_roughconductor
BIN=$TARGET/release/peer_roughconductor

# --- 4. Pairs, Mitsuba, the crate, the comparison -------------------------------------------
PAIRS=$WORK/pairs-$N.bin
"$py" "$PEERS" gen --n "$N" --out "$PAIRS"
"$py" "$PEERS" workload --variant "$VARIANT" --alpha "$ALPHA" --out "$WORK/workload.json"
read -r ETA K < <("$py" -c "import json; w = json.load(open('$WORK/workload.json'))
print(','.join(repr(x) for x in w['eta']), ','.join(repr(x) for x in w['k']))")

echo "== Mitsuba roughconductor eval: $N pairs, $REPS repetitions"
"$py" "$PEERS" eval --variant "$VARIANT" --alpha "$ALPHA" --pairs "$PAIRS" --reps "$REPS" \
    --warmup "$WARMUP" --out "$WORK/mitsuba-eval.bin" --timing "$WORK/mitsuba-eval.json"
STATUS=0
# GgxIsotropic: the crate's isotropic GGX type; ggx: its anisotropy-capable Ggx (as Mitsuba's);
# -shared: the conductor with SharedDivision (one division for the three channels where
# brdf::batch::shares_divisions(): Intel CPUs; the same as exact elsewhere); -newton: the same
# with brdf::fast::NewtonSqrtRecip<3, 3> (square roots and divisions by refined estimates,
# within a few ULP of the exact policy); -estimate: with brdf::fast::HardwareEstimate (the
# AVX-512 estimate instructions and one refinement step on Isa::Avx512, exact elsewhere);
# -estimate-shared: both (explicit lanes that share the division where shares_divisions());
# -fit: the conductor as brdf::fresnel::FittedConductor (a piecewise quintic in cos θd fitted
# at construction, within 2.5e-7 of the exact reflectance: no square root or division);
# -estimate-fit: that with HardwareEstimate.
for V in isotropic ggx isotropic-shared ggx-shared isotropic-newton ggx-newton isotropic-estimate \
    isotropic-estimate-shared isotropic-fit isotropic-estimate-fit; do
    NDF=${V%%-*}
    POLICY=exact
    [ "$V" = "$NDF" ] || POLICY=${V#*-}
    echo "== brdf batch::eval ($V): $N pairs, $REPS repetitions"
    "$BIN" --pairs "$PAIRS" --alpha "$ALPHA" --eta "$ETA" --k "$K" --ndf "$NDF" --policy "$POLICY" \
        --reps "$REPS" --warmup "$WARMUP" --values "$WORK/brdf-eval-$V.bin" --timing "$WORK/brdf-eval-$V.json"
    echo "== values ($V)"
    "$py" "$PEERS" compare --pairs "$PAIRS" --mitsuba "$WORK/mitsuba-eval.bin" \
        --brdf "$WORK/brdf-eval-$V.bin" --workload "$WORK/workload.json" --tolerance "$TOLERANCE" \
        --out "$WORK/compare-$V.json" || STATUS=1
done

if [ "$SAMPLE" = 1 ]; then
    echo "== Mitsuba roughconductor sample: $N pairs, $REPS repetitions"
    "$py" "$PEERS" sample --variant "$VARIANT" --alpha "$ALPHA" --pairs "$PAIRS" --reps "$REPS" \
        --warmup "$WARMUP" --out "$WORK/mitsuba-sample.bin" --timing "$WORK/mitsuba-sample.json"
    # vndf: visible normals (as Mitsuba); caps: the crate's default spherical caps; -shared:
    # the conductor with SharedDivision (as for eval); -estimate: with HardwareEstimate
    # (explicit 16-lane registers and the estimate instructions on AVX-512); -fit: the
    # conductor as FittedConductor (as for eval).
    for ST in vndf caps vndf-shared caps-shared vndf-estimate caps-estimate caps-estimate-shared \
        vndf-fit caps-fit; do
        STRATEGY=${ST%%-*}
        POLICY=exact
        [ "$ST" = "$STRATEGY" ] || POLICY=${ST#*-}
        echo "== brdf batch::sample (GgxIsotropic, $ST): $N pairs, $REPS repetitions"
        "$BIN" --mode sample --strategy "$STRATEGY" --policy "$POLICY" --pairs "$PAIRS" \
            --alpha "$ALPHA" --eta "$ETA" --k "$K" --reps "$REPS" --warmup "$WARMUP" \
            --values "$WORK/brdf-sample-$ST.bin" --timing "$WORK/brdf-sample-$ST.json"
        echo "== samples ($ST)"
        "$py" "$PEERS" compare-sample --pairs "$PAIRS" --mitsuba "$WORK/mitsuba-sample.bin" \
            --brdf "$WORK/brdf-sample-$ST.bin" --workload "$WORK/workload.json" \
            --out "$WORK/compare-sample-$ST.json" || STATUS=1
    done
fi

# --- 5. Summary -------------------------------------------------------------------------------
BRDF_VERSION="brdf $(git rev-parse --short HEAD 2>/dev/null || echo '(no git)'), $(rustc --version)"
CPU=$(lscpu | sed -n 's/^Model name: *//p' | head -n1)
FAMILY=$(lscpu | sed -n 's/^CPU family: *//p' | head -n1)
"$py" - "$WORK" "$CPU" "$FAMILY" "$LLVM_VERSION" "$SAMPLE" "$BRDF_VERSION" <<'EOF'
import json, os, sys
work, cpu, family, llvm, sample, brdf = sys.argv[1:]
load = lambda name: json.load(open(os.path.join(work, name)))
w, m = load("workload.json"), load("mitsuba-eval.json")
VARIANTS = (("isotropic", "GgxIsotropic"), ("ggx", "Ggx"),
            ("isotropic-shared", "GgxIsotropic, SharedDivision"),
            ("ggx-shared", "Ggx, SharedDivision"),
            ("isotropic-newton", "GgxIsotropic, NewtonSqrtRecip<3,3>"),
            ("ggx-newton", "Ggx, NewtonSqrtRecip<3,3>"),
            ("isotropic-estimate", "GgxIsotropic, HardwareEstimate"),
            ("isotropic-estimate-shared", "GgxIsotropic, HardwareEstimate, SharedDivision"),
            ("isotropic-fit", "GgxIsotropic, FittedConductor"),
            ("isotropic-estimate-fit", "GgxIsotropic, HardwareEstimate, FittedConductor"))
b, c = {}, {}
for ndf, _ in VARIANTS:
    b[ndf], c[ndf] = load(f"brdf-eval-{ndf}.json"), load(f"compare-{ndf}.json")
n = m["n"]
rate = lambda s: n / s / 1e6
rgb = lambda v: "(" + ", ".join(f"{x:.6g}" for x in v) + ")"
print(f"\nroughconductor eval, {n} pairs, one thread: GGX alpha = {w['alpha']:.6g}, separable "
      f"Smith G1*G1, exact conductor Fresnel with Mitsuba's RGB gold (eta = {rgb(w['eta'])}, "
      f"k = {rgb(w['k'])}), times the cosine of the light direction")
load_avg = " ".join(f"{x:.2f}" for x in os.getloadavg())
print(f"  CPU: {cpu} (family {family}); load average: {load_avg}")
jit = "loaded from Dr.Jit's disk cache" if m["compile_ms"] == 0 else f"{m['compile_ms']:.0f} ms"
print(f"  Mitsuba {w['mitsuba']}, Dr.Jit {w['drjit']}, {w['variant']}, {w['threads']} thread "
      f"(process CPU / wall {m['cpu_per_wall']:.2f}), {llvm}; JIT compilation ({jit}) excluded")
shares = b["isotropic"].get("shares_divisions", False)
print(f"  {brdf}, release build; batch::shares_divisions() = {shares}")
print(f"  {'M evaluations/s':48} {'median':>8} {'best':>8}   ({m['reps']} repetitions)")
rows = [("Mitsuba, per call (trace + kernel)", m["wall_median_s"], m["wall_best_s"]),
        ("Mitsuba, kernel alone", m["kernel_median_s"], m["kernel_best_s"])]
for ndf, name in VARIANTS:
    rows.append((f"brdf, {name} ({b[ndf]['isa']})", b[ndf]["median_s"], b[ndf]["best_s"]))
for name, med, best in rows:
    print(f"  {name:48} {rate(med):8.1f} {rate(best):8.1f}")
for ndf, name in VARIANTS:
    t = b[ndf]["median_s"]
    print(f"  ratio brdf ({name}) / Mitsuba, medians: {m['wall_median_s'] / t:.2f}x per call, "
          f"{m['kernel_median_s'] / t:.2f}x against the kernel alone")
for ndf, name in VARIANTS:
    e = c[ndf]
    print(f"  values ({name}): max relative error {e['max_rel_error']:.2e} (99.9 % below "
          f"{e['p999_rel_error']:.2e}, mean {e['mean_rel_error']:.2e}); against f64: Mitsuba "
          f"{e['mitsuba_vs_f64']['max_rel_error']:.2e}, brdf {e['brdf_vs_f64']['max_rel_error']:.2e}")
if sample == "1":
    s = load("mitsuba-sample.json")
    print(f"\nroughconductor sample, {n} pairs, one thread (M samples/s, medians of {s['reps']}):")
    print(f"  {'Mitsuba, per call (trace + kernel)':46} {rate(s['wall_median_s']):8.1f}")
    print(f"  {'Mitsuba, kernel alone':46} {rate(s['kernel_median_s']):8.1f}")
    for st, name in (("vndf", "visible normals"), ("caps", "spherical caps"),
                     ("vndf-shared", "vis. normals, shared div."),
                     ("caps-shared", "caps, shared division"),
                     ("vndf-estimate", "vis. normals, estimates"),
                     ("caps-estimate", "caps, estimates"),
                     ("caps-estimate-shared", "caps, estimates, shared div."),
                     ("vndf-fit", "vis. normals, fitted Fresnel"),
                     ("caps-fit", "caps, fitted Fresnel")):
        t, e = load(f"brdf-sample-{st}.json"), load(f"compare-sample-{st}.json")
        print(f"  brdf, GgxIsotropic, {name:26} {rate(t['median_s']):8.1f}   "
              f"({t['isa']}; {s['wall_median_s'] / t['median_s']:.2f}x per call, "
              f"{s['kernel_median_s'] / t['median_s']:.2f}x the kernel)")
        print(f"    mean weight z (brdf - Mitsuba): {', '.join(f'{x:+.2f}' for x in e['mean_weight_z'])}; "
              f"weight vs f64 (99.9 %): brdf {e['brdf']['weight_p999_rel_error']:.1e}, "
              f"Mitsuba {e['mitsuba']['weight_p999_rel_error']:.1e}")
EOF
if [ "$STATUS" != 0 ]; then
    echo "run.sh: FAIL: the values disagree (see above and $WORK/compare-*.json)" >&2
fi
exit "$STATUS"
