"""The Mitsuba 3 half of the peer benchmark (see run.sh, which drives it).

Subcommands:
  gen      N direction pairs (and sampling uniforms) with a fixed seed -> pairs file
  workload Mitsuba's roughconductor parameters as it evaluates them (alpha, RGB eta, k)
  eval     time Mitsuba's roughconductor `eval` on the pairs, write its values
  sample   time Mitsuba's roughconductor `sample` on the pairs, write its results
  compare  check the crate's values against Mitsuba's, print the summary
  compare-sample  check both sides' samples against an f64 reference (density and weight at
           the drawn direction) and their mean weights against each other (4 sigma)

File formats (little-endian; written here and read by tools/src/bin/peer_roughconductor.rs):
  pairs:  b"BRDFPR01", u64 N, then f32 arrays of N each:
          wi.x wi.y wi.z wo.x wo.y wo.z uc u0 u1
          in this crate's naming: wi towards the light, wo towards the viewer, both unit
          vectors in the local frame (z = normal) strictly above the horizon; uc, u0, u1
          uniform in [0, 1) for sampling.
  values: b"BRDFVL01", u64 N, u64 C, then C f32 arrays of N each.

Naming: Mitsuba's `eval(ctx, si, wo)` takes si.wi (towards the viewer, where the path came
from) and wo (towards the light, the direction it samples), and returns f * cos(theta) of
ITS wo. In this crate's naming that is f(wi, wo) * wi.z: Mitsuba's si.wi is our wo and
Mitsuba's wo is our wi.
"""

import argparse
import json
import struct
import sys
import time

import numpy as np

PAIRS_MAGIC = b"BRDFPR01"
VALUES_MAGIC = b"BRDFVL01"
# The arrays of a pairs file, in order.
PAIR_FIELDS = ("wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "uc", "u0", "u1")


def write_pairs(path, arrays):
    n = len(arrays[0])
    with open(path, "wb") as f:
        f.write(PAIRS_MAGIC + struct.pack("<Q", n))
        for a in arrays:
            f.write(np.ascontiguousarray(a, dtype="<f4").tobytes())


def read_pairs(path):
    with open(path, "rb") as f:
        head = f.read(16)
        if head[:8] != PAIRS_MAGIC:
            sys.exit(f"{path}: not a pairs file")
        (n,) = struct.unpack("<Q", head[8:])
        data = np.frombuffer(f.read(), dtype="<f4")
    if data.size != n * len(PAIR_FIELDS):
        sys.exit(f"{path}: expected {n * len(PAIR_FIELDS)} floats, found {data.size}")
    return dict(zip(PAIR_FIELDS, data.reshape(len(PAIR_FIELDS), n)))


def write_values(path, channels):
    channels = [np.ascontiguousarray(c, dtype="<f4") for c in channels]
    with open(path, "wb") as f:
        f.write(VALUES_MAGIC + struct.pack("<QQ", channels[0].size, len(channels)))
        for c in channels:
            f.write(c.tobytes())


def read_values(path):
    with open(path, "rb") as f:
        head = f.read(24)
        if head[:8] != VALUES_MAGIC:
            sys.exit(f"{path}: not a values file")
        n, c = struct.unpack("<QQ", head[8:])
        data = np.frombuffer(f.read(), dtype="<f4")
    if data.size != n * c:
        sys.exit(f"{path}: expected {n * c} floats, found {data.size}")
    return data.reshape(c, n)


def hemisphere(rng, n):
    """Uniform directions on the open upper hemisphere: cos(theta) = 1 - u in (0, 1]."""
    z = 1.0 - rng.random(n)
    phi = 2.0 * np.pi * rng.random(n)
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    return [r * np.cos(phi), r * np.sin(phi), z]


def cmd_gen(a):
    rng = np.random.default_rng(a.seed)
    wi = hemisphere(rng, a.n)
    wo = hemisphere(rng, a.n)
    u = [rng.random(a.n) for _ in range(3)]
    arrays = [np.asarray(x, dtype=np.float32) for x in wi + wo + u]
    # Rounding to f32 can turn a uniform just below 1 into 1.0: keep them in [0, 1).
    for x in arrays[6:]:
        np.minimum(x, np.float32(1.0) - np.float32(2.0**-24), out=x)
    assert all((arrays[i] > 0).all() for i in (2, 5)), "a direction on the horizon"
    write_pairs(a.out, arrays)


def mitsuba(variant):
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(variant)
    # One worker thread: the crate's batch path runs on one core.
    dr.set_thread_count(1)
    return dr, mi


def load_bsdf(mi, alpha):
    # GGX, the default separable Smith masking of Mitsuba's microfacet distribution,
    # the exact conductor Fresnel with Mitsuba's built-in gold ("Au") complex IOR.
    return mi.load_dict(
        {"type": "roughconductor", "distribution": "ggx", "alpha": alpha, "material": "Au"}
    )


def cmd_workload(a):
    dr, mi = mitsuba(a.variant)
    bsdf = load_bsdf(mi, a.alpha)
    params = mi.traverse(bsdf)
    # The RGB values the eta and k textures hold, i.e. what the variant evaluates
    # (Mitsuba converts its spectral gold data to RGB at load time in RGB variants).
    def rgb(key):
        v = np.array(params[key], dtype=np.float32).ravel()
        assert v.size == 3, (key, v)
        return [float(x) for x in v]

    alpha = np.array(params["alpha.value"], dtype=np.float32).ravel()
    out = {
        "alpha": float(alpha[0]),
        "eta": rgb("eta.value"),
        "k": rgb("k.value"),
        "mitsuba": mi.__version__,
        "drjit": dr.__version__,
        "variant": a.variant,
        "threads": dr.thread_count(),
    }
    with open(a.out, "w") as f:
        json.dump(out, f, indent=1)


def time_reps(dr, run, warmup, reps):
    """Per-repetition wall times (s) of `run` and the JIT kernels' own execution times."""
    dr.set_flag(dr.JitFlag.KernelHistory, True)
    result = None
    for _ in range(warmup):  # the first call traces and compiles; the rest hit the cache
        result = run()
    history = dr.kernel_history()  # returns and clears the history
    # LLVM compile time of the warm-up kernels; 0 when they came from the disk cache.
    compile_ms = sum(k.get("backend_time", 0.0) for k in history)
    walls = []
    cpu0, wall0 = time.process_time(), time.perf_counter()
    for _ in range(reps):
        t = time.perf_counter()
        result = run()
        walls.append(time.perf_counter() - t)
    cpu1, wall1 = time.process_time(), time.perf_counter()
    history = dr.kernel_history()
    dr.set_flag(dr.JitFlag.KernelHistory, False)
    jit = [k for k in history if k["type"] == dr.KernelType.JIT]
    misses = sum(1 for k in jit if not k.get("cache_hit", 0))
    if misses:
        sys.exit(f"{misses} kernels were compiled inside the timed loop: raise --warmup")
    # Kernel execution time per repetition (ms in the history), summed over the kernels
    # a repetition launches.
    per_rep = len(jit) / reps
    kernel = np.array([k["execution_time"] for k in jit]) * 1e-3
    if per_rep != int(per_rep) or per_rep < 1:
        sys.exit(f"{len(jit)} kernels in {reps} repetitions")
    kernel = kernel.reshape(reps, int(per_rep)).sum(axis=1)
    timing = {
        "wall_median_s": float(np.median(walls)),
        "wall_best_s": float(np.min(walls)),
        "kernel_median_s": float(np.median(kernel)),
        "kernel_best_s": float(np.min(kernel)),
        "kernels_per_rep": int(per_rep),
        "compile_ms": compile_ms,
        # ~1 for one thread doing the work while the caller waits.
        "cpu_per_wall": (cpu1 - cpu0) / (wall1 - wall0),
        "reps": reps,
    }
    return result, timing


def surface(dr, mi, p):
    """Mitsuba's view of the pairs: si.wi is our wo (towards the viewer)."""
    si = dr.zeros(mi.SurfaceInteraction3f)
    si.wi = mi.Vector3f(p["wo_x"], p["wo_y"], p["wo_z"])
    return si


def cmd_eval(a):
    dr, mi = mitsuba(a.variant)
    bsdf = load_bsdf(mi, a.alpha)
    p = read_pairs(a.pairs)
    si = surface(dr, mi, p)
    # Mitsuba's wo is our wi (towards the light).
    wo = mi.Vector3f(p["wi_x"], p["wi_y"], p["wi_z"])
    ctx = mi.BSDFContext()
    dr.eval(si, wo)
    dr.sync_thread()

    def run():
        v = bsdf.eval(ctx, si, wo)
        dr.eval(v)
        dr.sync_thread()
        return v

    v, timing = time_reps(dr, run, a.warmup, a.reps)
    write_values(a.out, np.array(v, dtype=np.float32))
    timing["n"] = int(p["wi_x"].size)
    with open(a.timing, "w") as f:
        json.dump(timing, f, indent=1)


def cmd_sample(a):
    dr, mi = mitsuba(a.variant)
    bsdf = load_bsdf(mi, a.alpha)
    p = read_pairs(a.pairs)
    si = surface(dr, mi, p)
    uc = mi.Float(p["uc"])
    u = mi.Point2f(p["u0"], p["u1"])
    ctx = mi.BSDFContext()
    dr.eval(si, uc, u)
    dr.sync_thread()

    def run():
        bs, weight = bsdf.sample(ctx, si, uc, u)
        dr.eval(bs.wo, bs.pdf, weight)
        dr.sync_thread()
        return bs, weight

    (bs, weight), timing = time_reps(dr, run, a.warmup, a.reps)
    # Drawn direction (our wi), its density per solid angle, f * cos / pdf per channel.
    wi = np.array(bs.wo, dtype=np.float32)
    pdf = np.array(bs.pdf, dtype=np.float32).reshape(1, -1)
    w = np.array(weight, dtype=np.float32)
    write_values(a.out, np.concatenate([wi, pdf, w]))
    timing["n"] = int(p["wi_x"].size)
    with open(a.timing, "w") as f:
        json.dump(timing, f, indent=1)


def rel_error(a, b):
    """|a - b| / max(|a|, |b|) per element (0 where both are 0)."""
    a, b = a.astype(np.float64), b.astype(np.float64)
    scale = np.maximum(np.abs(a), np.abs(b))
    return np.where(scale > 0, np.abs(a - b) / np.where(scale > 0, scale, 1.0), 0.0)


def reference(p, alpha, eta, k):
    """The workload in f64 from the f32 pairs, written independently of both sides:
    F(wi.h) D(h) G1(wi) G1(wo) / (4 wi.z wo.z) * wi.z per channel, with GGX's
    D = a^2 / (pi ((a^2 - 1) cos^2 + 1)^2), Smith's G1 = 2 / (1 + sqrt(1 + a^2 tan^2)) and the
    Fresnel reflectance of the complex IOR n = eta + i k from the s and p amplitudes
    (cos - t) / (cos + t) and (n^2 cos - t) / (n^2 cos + t), t = sqrt(n^2 - sin^2)."""
    wi = np.array([p["wi_x"], p["wi_y"], p["wi_z"]], dtype=np.float64)
    wo = np.array([p["wo_x"], p["wo_y"], p["wo_z"]], dtype=np.float64)
    h = wi + wo
    h /= np.linalg.norm(h, axis=0)
    a2 = float(alpha) ** 2
    c2 = h[2] ** 2
    d = a2 / (np.pi * ((a2 - 1.0) * c2 + 1.0) ** 2)

    def g1(w):
        tan2 = (w[0] ** 2 + w[1] ** 2) / w[2] ** 2
        return 2.0 / (1.0 + np.sqrt(1.0 + a2 * tan2))

    cos_d = np.sum(wi * h, axis=0)
    out = []
    for e, kk in zip(eta, k):
        n2 = complex(e, kk) ** 2
        t = np.sqrt(n2 - (1.0 - cos_d**2) + 0j)
        rs = (cos_d - t) / (cos_d + t)
        rp = (n2 * cos_d - t) / (n2 * cos_d + t)
        f = 0.5 * (np.abs(rs) ** 2 + np.abs(rp) ** 2)
        out.append(f * d * g1(wi) * g1(wo) / (4.0 * wo[2]))
    return np.array(out)


def cmd_compare(a):
    ref = read_values(a.mitsuba)
    ours = read_values(a.brdf)
    if ref.shape != ours.shape:
        sys.exit(f"shapes differ: Mitsuba {ref.shape}, brdf {ours.shape}")
    finite = np.isfinite(ours).all() and np.isfinite(ref).all()
    err = rel_error(ref, ours)
    worst = np.unravel_index(np.argmax(err), err.shape)
    p = read_pairs(a.pairs)
    i = worst[1]
    zero_mismatch = int(np.count_nonzero((ref == 0) != (ours == 0)))
    result = {
        "max_rel_error": float(err.max()),
        "p999_rel_error": float(np.quantile(err, 0.999)),
        "mean_rel_error": float(err.mean()),
        "worst": {
            "channel": int(worst[0]),
            "index": int(i),
            "wi": [float(p[f"wi_{c}"][i]) for c in "xyz"],
            "wo": [float(p[f"wo_{c}"][i]) for c in "xyz"],
            "mitsuba": float(ref[worst]),
            "brdf": float(ours[worst]),
        },
        "zero_mismatch": zero_mismatch,
        "finite": bool(finite),
    }
    with open(a.workload) as f:
        w = json.load(f)
    exact = reference(p, w["alpha"], w["eta"], w["k"])
    for name, v in (("mitsuba", ref), ("brdf", ours)):
        e = rel_error(v, exact)
        result[f"{name}_vs_f64"] = {"max_rel_error": float(e.max()), "mean_rel_error": float(e.mean())}
    with open(a.out, "w") as f:
        json.dump(result, f, indent=1)
    wst = result["worst"]
    print(f"max relative error {err.max():.2e} at pair {i} channel {worst[0]} "
          f"(wi.z = {wst['wi'][2]:.3g}, wo.z = {wst['wo'][2]:.3g}: Mitsuba {wst['mitsuba']:.9g}, "
          f"brdf {wst['brdf']:.9g}); zero/non-zero mismatches: {zero_mismatch}")
    print(f"against an f64 reference: Mitsuba {result['mitsuba_vs_f64']['max_rel_error']:.2e}, "
          f"brdf {result['brdf_vs_f64']['max_rel_error']:.2e} max relative error")
    if not finite or zero_mismatch or err.max() > a.tolerance:
        sys.exit(f"FAIL: values disagree (max relative error {err.max():.3g} > {a.tolerance:g}, "
                 f"{zero_mismatch} zero/non-zero mismatches, finite: {finite})")


def sample_reference(p, wi, alpha, eta, k):
    """f64 density and weight of visible-normal sampling at the drawn directions wi (3 x N):
    pdf = D(h) G1(wo) / (4 wo.z) (Heitz 2018; spherical caps draw the same density) and
    weight = f cos(theta_i) / pdf, from `reference` with wi replaced."""
    q = dict(p)
    q["wi_x"], q["wi_y"], q["wi_z"] = wi
    wo = np.array([p["wo_x"], p["wo_y"], p["wo_z"]], dtype=np.float64)
    wi = np.asarray(wi, dtype=np.float64)
    h = wi + wo
    h /= np.linalg.norm(h, axis=0)
    a2 = float(alpha) ** 2
    d = a2 / (np.pi * ((a2 - 1.0) * h[2] ** 2 + 1.0) ** 2)
    tan2 = (wo[0] ** 2 + wo[1] ** 2) / wo[2] ** 2
    g1_wo = 2.0 / (1.0 + np.sqrt(1.0 + a2 * tan2))
    pdf = d * g1_wo / (4.0 * wo[2])
    f_cos = reference(q, alpha, eta, k)
    return pdf, f_cos / pdf


def cmd_compare_sample(a):
    """Samples from different warps of the same uniforms differ one by one, so the check is
    per side against the f64 reference at its own directions, and the mean weight (the
    directional albedo averaged over the pairs' wo) between the sides."""
    p = read_pairs(a.pairs)
    with open(a.workload) as f:
        w = json.load(f)
    result = {}
    means = {}
    for name, path in (("mitsuba", a.mitsuba), ("brdf", a.brdf)):
        v = read_values(path).astype(np.float64)
        if v.shape[0] != 7:
            sys.exit(f"{path}: expected 7 arrays (wi, pdf, weight), found {v.shape[0]}")
        wi, pdf, weight = v[:3], v[3], v[4:]
        valid = (pdf > 0) & (wi[2] > 0)
        pv = {key: x[valid] for key, x in p.items()}
        ref_pdf, ref_w = sample_reference(pv, wi[:, valid], w["alpha"], w["eta"], w["k"])
        e_pdf = rel_error(pdf[valid], ref_pdf)
        e_w = rel_error(weight[:, valid], ref_w)
        result[name] = {
            "valid": float(valid.mean()),
            "finite": bool(np.isfinite(v).all()),
            "pdf_max_rel_error": float(e_pdf.max()),
            "pdf_p999_rel_error": float(np.quantile(e_pdf, 0.999)),
            "weight_max_rel_error": float(e_w.max()),
            "weight_p999_rel_error": float(np.quantile(e_w, 0.999)),
            "mean_weight": [float(x) for x in weight.mean(axis=1)],
        }
        means[name] = (weight.mean(axis=1), weight.var(axis=1) / weight.shape[1])
    (mm, vm), (mb, vb) = means["mitsuba"], means["brdf"]
    z = (mb - mm) / np.sqrt(vm + vb)
    result["mean_weight_z"] = [float(x) for x in z]
    with open(a.out, "w") as f:
        json.dump(result, f, indent=1)
    for name in ("mitsuba", "brdf"):
        r = result[name]
        print(f"{name}: {100 * r['valid']:.2f} % valid; against f64 at its own directions: pdf "
              f"max {r['pdf_max_rel_error']:.2e} (99.9 % {r['pdf_p999_rel_error']:.2e}), weight "
              f"max {r['weight_max_rel_error']:.2e} (99.9 % {r['weight_p999_rel_error']:.2e}); "
              f"mean weight {', '.join(f'{x:.5f}' for x in r['mean_weight'])}")
    print(f"mean weight brdf - Mitsuba in standard errors: {', '.join(f'{x:+.2f}' for x in z)}")
    bad = [n for n in ("mitsuba", "brdf") if not result[n]["finite"]
           or result[n]["pdf_p999_rel_error"] > a.tolerance
           or result[n]["weight_p999_rel_error"] > a.tolerance]
    if bad or (np.abs(z) > 4).any():
        sys.exit(f"FAIL: samples disagree ({', '.join(bad) or 'mean weights beyond 4 sigma'})")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("gen")
    g.add_argument("--n", type=int, default=65536)
    g.add_argument("--seed", type=int, default=14)
    g.add_argument("--out", required=True)
    for name in ("workload", "eval", "sample"):
        s = sub.add_parser(name)
        s.add_argument("--variant", default="llvm_ad_rgb")
        s.add_argument("--alpha", type=float, default=0.3)
        s.add_argument("--out", required=True)
        if name != "workload":
            s.add_argument("--pairs", required=True)
            s.add_argument("--timing", required=True)
            s.add_argument("--reps", type=int, default=1000)
            s.add_argument("--warmup", type=int, default=20)
    c = sub.add_parser("compare")
    c.add_argument("--pairs", required=True)
    c.add_argument("--mitsuba", required=True)
    c.add_argument("--brdf", required=True)
    c.add_argument("--workload", required=True)
    c.add_argument("--tolerance", type=float, default=1e-5)
    c.add_argument("--out", required=True)
    c = sub.add_parser("compare-sample")
    c.add_argument("--pairs", required=True)
    c.add_argument("--mitsuba", required=True)
    c.add_argument("--brdf", required=True)
    c.add_argument("--workload", required=True)
    c.add_argument("--tolerance", type=float, default=1e-4)
    c.add_argument("--out", required=True)
    a = ap.parse_args()
    {"gen": cmd_gen, "workload": cmd_workload, "eval": cmd_eval, "sample": cmd_sample,
     "compare": cmd_compare, "compare-sample": cmd_compare_sample}[a.cmd](a)


if __name__ == "__main__":
    main()
