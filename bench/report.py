#!/usr/bin/env python3
"""Writes report.md and accuracy_vs_time.png from a dstrans bench results.json (dstrans bench runs it).

usage: report.py RESULTS_JSON OUT_DIR
The thesis's Tables 4.1-4.7 are reproduced as ratios, ours beside the thesis's (GTX 760, 1920x1080).
"""
import json
import os
import sys

# The thesis's figures (TECHNIQUES.md, S0).
THESIS = {
    "targets": {"interlaced": 5, "peeling": 10, "forward-depth": 3, "forward": 2},
    "refraction_cost": "11% with no lights (564 -> 499 fps), 4% at 64 lights (148 -> 142)",
    "shadow_cost": "13% at 2 lights (394 -> 343 fps), 34% at 64 (53 -> 35)",
    "vs_peeling": "1.2x to 1.6x faster with shadows, 1.8x to 2.0x without",
    "vs_forward": "slower at 2-4 lights, faster from 8 (up to 1.57x with shadows at 32, 3.9x without at 64)",
    "shares": "no consistent difference between 35%, 17% and 0% transparent triangles (within +-2 fps)",
}


def find(results, **want):
    for r in results:
        s = r["settings"]
        if all((r.get(k) if k in ("technique", "scene") else s.get(k, [] if k == "forced" else None)) == v
               for k, v in want.items()):
            return r
    return None


def ms(r):
    return None if r is None else r["frame_ms"]


def pct(a, b):
    return "n/a" if a is None or b is None or b == 0 else "%+.0f%%" % (100.0 * (a - b) / b)


def ratio(a, b):
    return "n/a" if a is None or b is None or b == 0 else "%.2fx" % (a / b)


# SSIM and FLIP over all pixels and over the pixels a comparison is about: the table columns and a record's cells.
SSIM_FLIP_HEAD = "SSIM | SSIM on glass | FLIP | FLIP on glass"


def exact(r, key="rmse"):
    """A record's figure against the exact reference: "-" where there is none, "overflow" where its lists overflowed."""
    e = r.get("exact")
    if e is None:
        return "-"
    if e["overflow"]:
        return "overflow (%d)" % e["overflow"]
    return "%.2f" % e[key]


def ssim_flip(r):
    return "%.4f | %.4f | %.4f | %.4f" % (r["ssim"], r["ssim_transparent"], r["flip"], r["flip_transparent"])


def main():
    results_path, out = sys.argv[1], sys.argv[2]
    everything = json.load(open(results_path))
    results = [r for r in everything
               if r["scene"] not in ("hair", "smoke", "glass_room_post", "glass_room_reconstruct", "glass_room_specular",
                                     "glass_room_path", "glass_room_shadows", "glass_shelf", "hair_panes",
                                     "glass_room_smoke")
               and not r["scene"].endswith("_paired")]  # the thesis's comparisons
    layers = [r for r in everything if r["scene"] == "hair"]   # S1
    volumes = [r for r in everything if r["scene"] == "smoke"]  # S2
    post = [r for r in everything if r["scene"] == "glass_room_post"]  # S3
    sweep = [r for r in everything if r["scene"] == "glass_room_reconstruct"]
    specular = [r for r in everything if r["scene"] == "glass_room_specular"]
    paths = [r for r in everything if r["scene"] == "glass_room_path"]  # temporal interlacing
    soft = [r for r in everything if r["scene"] == "glass_room_shadows"]
    shelf = [r for r in everything if r["scene"] == "glass_shelf"]  # glTF
    around = [r for r in everything if r["scene"] in ("hair_panes", "glass_room_smoke")]  # depth order across techniques
    paired = [r for r in everything if r["scene"].endswith("_paired")]
    lights = sorted({r["settings"]["lights"] for r in results})
    first = results[0]
    size = "%dx%d" % (first["settings"]["width"], first["settings"]["height"])
    lines = []
    w = lines.append
    w("# dstrans bench: the thesis's comparisons on this machine")
    w("")
    w("Backend %s on %s (%s), %s pixels, glass_room%s, the median of %d frames per run; times are GPU "
      "milliseconds per frame from timestamp queries. The reference for every error figure is deferred depth "
      "peeling at the same settings; RMSE is over 0-255 channel values, on all pixels and on pixels the "
      "reference's first layer covers with glass; SSIM (Wang et al. 2004: 1 for equal images) and LDR-FLIP "
      "(Andersson et al. 2020: 0 for equal images, towards 1 as a difference grows visible, for an observer "
      "seeing 67 pixels a degree) are the means of their maps over the same pixels." % (
          first["backend"], first["device"], first["driver"], size,
          " ({:,} triangles)".format(first["triangles"]) if "triangles" in first else "", first["settings"]["frames"]))
    w("")
    write_machine(w, first, results)
    w("")

    if paired:
        write_paired(w, paired)
    write_limits(w, results)

    w("## Table 4.1: render targets and memory")
    w("")
    w("| technique | targets (ours) | targets (thesis) | bytes a pixel |")
    w("|---|---|---|---|")
    for t in ("interlaced", "peeling", "forward-depth", "forward"):
        r = find(results, technique=t)
        if r:
            w("| %s | %d | %d | %d |" % (t, r["render_targets"], THESIS["targets"][t], r["bytes_per_pixel"]))
    w("")

    w("## Table 4.2: the cost of refraction (interlaced, no shadows)")
    w("")
    w("| lights | with refraction (ms) | without (ms) | cost |")
    w("|---|---|---|---|")
    for n in lights:
        a = find(results, technique="interlaced", scene="glass_room", lights=n, shadows="off", refraction=True)
        b = find(results, technique="interlaced", scene="glass_room", lights=n, shadows="off", refraction=False)
        if a and b:
            w("| %d | %.2f | %.2f | %s |" % (n, ms(a), ms(b), pct(ms(a), ms(b))))
    w("")
    spread = sorted(r["frame_ms_spread"] for r in results)[len(results) // 2]
    w("Thesis: %s. Here the median interquartile spread of a run's frames is %.2f ms, so a difference "
      "smaller than that is noise, not a cost." % (THESIS["refraction_cost"], spread))
    w("")

    w("## Table 4.3: transparent against opaque shadows (interlaced)")
    w("")
    w("| lights | transparent (ms) | opaque (ms) | cost |")
    w("|---|---|---|---|")
    for n in lights:
        a = find(results, technique="interlaced", scene="glass_room", lights=n, shadows="transparent", refraction=True)
        b = find(results, technique="interlaced", scene="glass_room", lights=n, shadows="opaque", refraction=True)
        if a and b:
            w("| %d | %.2f | %.2f | %s |" % (n, ms(a), ms(b), pct(ms(a), ms(b))))
    w("")
    costs = []
    for n in lights:
        a = find(results, technique="interlaced", scene="glass_room", lights=n, shadows="transparent", refraction=True)
        b = find(results, technique="interlaced", scene="glass_room", lights=n, shadows="opaque", refraction=True)
        if a and b:
            costs.append("%s at %d lights" % (pct(ms(a), ms(b)), n))
    w("Thesis: %s. Here: %s. Transparent shadows add one RGBA8 target to each shadow pass and a second "
      "texel and the Eq. 3.1 selection to each lookup." % (THESIS["shadow_cost"], ", ".join(costs) or "not measured"))
    w("")
    write_shadow_kinds(w, paired, soft)

    for shadows, title in (("transparent", "Table 4.4: with transparent shadows"), ("off", "Table 4.5: without shadows")):
        w("## %s: interlaced against depth peeling and forward rendering" % title)
        w("")
        w("| lights | interlaced (ms) | peeling (ms) | speed-up | forward (ms) | speed-up | forward-depth (ms) | speed-up |")
        w("|---|---|---|---|---|---|---|---|")
        for n in lights:
            if n == 0 and shadows != "off":
                continue
            i = find(results, technique="interlaced", scene="glass_room", lights=n, shadows=shadows, refraction=True)
            p = find(results, technique="peeling", scene="glass_room", lights=n, shadows=shadows, refraction=True)
            f = find(results, technique="forward", scene="glass_room", lights=n, shadows=shadows, refraction=True)
            d = find(results, technique="forward-depth", scene="glass_room", lights=n, shadows=shadows, refraction=True)
            if i:
                w("| %d | %.2f | %s | %s | %s | %s | %s | %s |" % (
                    n, ms(i), "%.2f" % ms(p) if p else "n/a", ratio(ms(p), ms(i)), "%.2f" % ms(f) if f else "n/a",
                    ratio(ms(f), ms(i)), "%.2f" % ms(d) if d else "n/a", ratio(ms(d), ms(i))))
        w("")
    def speedups(other, shadows):
        out = []
        for n in lights:
            i = find(results, technique="interlaced", scene="glass_room", lights=n, shadows=shadows, refraction=True)
            o = find(results, technique=other, scene="glass_room", lights=n, shadows=shadows, refraction=True)
            if i and o and (n > 0 or shadows == "off"):
                out.append((n, ms(o) / ms(i)))
        return out
    def span(v):
        return "%.2fx to %.2fx" % (min(x for _, x in v), max(x for _, x in v)) if v else "not measured"
    slower = [n for n, x in speedups("forward-depth", "transparent") + speedups("forward-depth", "off") if x < 1.0]
    w("Thesis: against peeling %s; against forward %s. Here: against peeling %s with shadows and %s "
      "without; against forward with depth %s with shadows and %s without%s. Peeling draws the scene twice "
      "and lights two G-buffers; forward rendering draws all geometry once per light." % (
          THESIS["vs_peeling"], THESIS["vs_forward"], span(speedups("peeling", "transparent")),
          span(speedups("peeling", "off")), span(speedups("forward-depth", "transparent")),
          span(speedups("forward-depth", "off")),
          "; forward is the faster at %s lights" % ", ".join(str(n) for n in sorted(set(slower))) if slower else ""))
    w("")

    w("## Tables 4.6 and 4.7: the share of transparent triangles (interlaced)")
    w("")
    w("| scene | transparent triangles | shadows (ms) | no shadows (ms) |")
    w("|---|---|---|---|")
    zero = [r for r in results if r["scene"] == "glass_room_0"]
    fixed = zero[0]["settings"]["lights"] if zero else None
    times = []
    for scene, share in (("glass_room", "37.5%"), ("glass_room_17", "17.1%"), ("glass_room_0", "0%")):
        a = find(results, technique="interlaced", scene=scene, lights=fixed, shadows="transparent", refraction=True,
                 forced=[])
        b = find(results, technique="interlaced", scene=scene, lights=fixed, shadows="off", refraction=True, forced=[])
        if a and b:
            w("| %s | %s | %.2f | %.2f |" % (scene, share, ms(a), ms(b)))
            times.append((ms(a), ms(b)))
    w("")
    if times:
        with_s, without = [t[0] for t in times], [t[1] for t in times]
        w("Thesis: %s. Here, at %d lights, the shares differ by at most %.0f%% with shadows and %.0f%% without "
          "(max against min). glass_room and glass_room_17 run the same passes; glass_room_0 has no glass, so "
          "its plan leaves out interlacing, refraction and the shadow-colour target (next section)."
          % (THESIS["shares"], fixed, 100 * (max(with_s) / min(with_s) - 1), 100 * (max(without) / min(without) - 1)))
    w("")
    base = find(results, technique="interlaced", scene="glass_room_0", lights=fixed, shadows="transparent",
                refraction=True, forced=[])
    forced = [r for r in results if r["settings"].get("forced")]
    if base and forced:
        w("## What an unused effect costs")
        w("")
        w("glass_room_0 (no glass, %d shadowed spot lights) with its own plan (%s), and with each effect it does "
          "not use forced into the pipeline (refraction brings transparency with it): the time and memory leaving "
          "it out saves. Memory is the plan's "
          "targets at %dx%d with %d^2 shadow maps." % (fixed, ", ".join(base["effects"]) or "plain deferred",
                                                       base["settings"]["width"], base["settings"]["height"],
                                                       base["settings"]["shadow_size"]))
        w("")
        w("| forced effect | ms | ms saved by leaving it out | memory (KiB) | KiB saved |")
        w("|---|---|---|---|---|")
        w("| none (the plan) | %.2f | | %.0f | |" % (ms(base), base["memory_bytes"] / 1024.0))
        for r in forced:
            w("| %s | %.2f | %.2f (%s) | %.0f | %.0f |" % (
                ", ".join(r["settings"]["forced"]), ms(r), ms(r) - ms(base), pct(ms(r), ms(base)),
                r["memory_bytes"] / 1024.0, (r["memory_bytes"] - base["memory_bytes"]) / 1024.0))
        w("")
        w("Timings on llvmpipe have a spread (frame_ms_spread in results.json); a saving within it is not "
          "measurable.")
        w("")

    w("## Accuracy against deferred depth peeling and the exact reference")
    w("")
    w("Each technique against peeling (two layers) and against the exact reference (`--technique reference`: "
      "every transparent fragment in per-pixel lists, sorted, shaded fully by every light, without refraction, "
      "so that refraction counts as error against it; peeling's own row says how far the thesis's reference is "
      "from it). \"overflow\" marks a reference whose lists overflowed, which is not used.")
    w("")
    w("| technique | lights | shadows | refraction | ms | RMSE | RMSE on glass | RMSE vs exact | on glass vs exact | PSNR (dB) | %s |"
      % SSIM_FLIP_HEAD)
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        if r["scene"] == "glass_room" and "exact" in r:
            s = r["settings"]
            w("| %s | %d | %s | %s | %.2f | %.2f | %.2f | %s | %s | %s | %s |" % (
                r["technique"], s["lights"], s["shadows"], "on" if s["refraction"] else "off", r["frame_ms"], r["rmse"],
                r["rmse_transparent"], exact(r), exact(r, "rmse_transparent"),
                "%.1f" % r["psnr"] if r["psnr"] is not None else "identical", ssim_flip(r)))
    w("")
    w("## Figure 4.7: refraction errors without depth")
    w("")
    w("Pixels where forward rendering without depth takes a moved sample that the depth test rejects (a "
      "foreground object leaks into the glass) or rejects one that the depth test takes (background beside "
      "the glass is lost). Techniques that reject by depth have none by construction.")
    w("")
    w("| technique | lights | shadows | foreground accepted | background rejected |")
    w("|---|---|---|---|---|")
    for r in results:
        s = r["settings"]
        if r["scene"] == "glass_room" and r["technique"].startswith("forward") and s["refraction"]:
            w("| %s | %d | %s | %d | %d |" % (r["technique"], s["lights"], s["shadows"],
                                             r["leak_pixels"]["foreground_accepted"], r["leak_pixels"]["background_rejected"]))
    w("")
    w("![accuracy against time](accuracy_vs_time.png)")
    w("")
    if layers:
        write_layers(w, layers)
    if volumes:
        write_volumes(w, volumes)
    if post:
        write_post(w, post)
    if sweep:
        write_sweep(w, sweep)
    if specular:
        write_specular(w, specular)
    if paths:
        write_paths(w, paths, paired)
    if shelf:
        write_gltf(w, shelf)
    if around:
        write_around_glass(w, around)
    open(os.path.join(out, "report.md"), "w").write("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=110)
    colours = {"interlaced": "tab:blue", "peeling": "tab:green", "forward": "tab:red", "forward-depth": "tab:orange"}
    for t, c in colours.items():
        pts = [(r["frame_ms"], r["rmse_transparent"]) for r in results if r["technique"] == t and r["scene"] == "glass_room"]
        if pts:
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], label=t, color=c, s=22)
    ax.set_xscale("log")
    ax.set_xlabel("frame time (ms, log scale)")
    ax.set_ylabel("RMSE on glass pixels against peeling (0-255)")
    ax.set_title("Accuracy against time, glass_room, every setting")
    ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "accuracy_vs_time.png"))
    if layers:
        plot_layers(plt, layers, os.path.join(out, "layers.png"))
    if volumes:
        plot_volumes(plt, volumes, os.path.join(out, "volumes.png"))
    if post:
        plot_post(plt, post, os.path.join(out, "post.png"))
    if sweep:
        plot_sweep(plt, sweep, os.path.join(out, "reconstruction.png"))


# S1's published figures (TECHNIQUES.md): at k = 8, RMSE 9 against forward over hair pixels, tailless 26,
# all-cheap 90; up to 75% faster than forward.
S1 = {"deferred": 9.0, "tailless": 26.0, "cheap": 90.0, "speedup": "up to 1.75x"}


def write_machine(w, first, results):
    """What makes this machine's times unlike the thesis's: a CPU rasteriser's cost model, and how much of a
    frame the shadow pass, which both techniques run alike, takes at the most lights."""
    device = first["device"]
    if any(name in device.lower() for name in ("llvmpipe", "lavapipe", "softpipe", "swiftshader")):
        threads = first.get("host_threads", 0)
        w("A CPU rasteriser is not a GTX 760: %s shades in JIT-compiled SIMD code on %s, so fragment work and "
          "memory traffic weigh far more, and fixed costs (a draw, a pass) far less, than on the thesis's GPU; "
          "vertices and triangle setup run on the CPU too. Ratios are the comparable figures; absolute times "
          "are not." % (device, "%d hardware threads" % threads if threads else "this machine's cores"))
    else:
        w("Ratios are the comparable figures; absolute times depend on the GPU (%s against the thesis's GTX 760)."
          % device)
    most = max(r["settings"]["lights"] for r in results)
    shared = [find(results, technique=t, scene="glass_room", lights=most, shadows="transparent", refraction=True, forced=[])
              for t in ("interlaced", "peeling")]
    if most > 0 and None not in shared and all("shadow" in r["pass_ms"] for r in shared):
        w("")
        w("Both techniques draw the same shadow maps, the scene once or twice from every light. At %d lights with "
          "transparent shadows the shadow pass takes %.1f of interlacing's %.1f ms (%.0f%%) and %.1f of peeling's "
          "%.1f ms: a cost they share, which draws peeling / interlaced towards 1 as it grows." % (
              most, shared[0]["pass_ms"]["shadow"], ms(shared[0]), 100.0 * shared[0]["pass_ms"]["shadow"] / ms(shared[0]),
              shared[1]["pass_ms"]["shadow"], ms(shared[1])))


def write_untimed(w, records):
    """A warning for each backend whose passes' timestamps miss part of a frame in any of `records`."""
    for backend in sorted({r["backend"] for r in records}):
        shares = [timed_share(r["pass_ms"], r["frame_ms"]) for r in records if r["backend"] == backend]
        worst = max(shares, key=lambda s: 0.0 if s is None else abs(s - 1.0))
        if not trusted(worst):
            w("On %s the passes' timestamps hold %s of a frame's time in the worst of these runs: that driver runs "
              "work outside them, so the pass times above (and any figure from them) are not to be trusted there; "
              "its frame times are." % (backend, "none" if worst is None else "%.0f%%" % (100.0 * worst)))
            w("")


def write_layers(w, layers):
    w("## Many layers: the k-buffer on hair (S1)")
    w("")
    zooms = sorted({r["settings"]["zoom"] for r in layers})
    w("hair.json at %d zoom levels. Time is the capture and resolve passes (GPU ms); speed-up is the forward "
      "reference's time over the variant's; RMSE (0-255) is against the forward reference (every fragment "
      "sorted and shaded fully) over the pixels hair covers, S1's convention. Bytes a pixel count the lists' "
      "heads and a pool of 16 nodes of 16 bytes, and the two tail targets, as nvpro's OIT samples list them. "
      "The deferred tail is shaded once a pixel from its fragments' gathered inputs, where S1 shades each. "
      "S1 measured at k = 8: RMSE %.0f (deferred), %.0f (tailless), %.0f (all cheap), %s faster than forward."
      % (len(zooms), S1["deferred"], S1["tailless"], S1["cheap"], S1["speedup"]))
    w("")
    w("| backend | zoom | hair pixels | mean layers | variant | k | ms | speed-up | RMSE on hair | bytes/px | %s |"
      % SSIM_FLIP_HEAD.replace("glass", "hair"))
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")

    def reference(r):
        return next(x for x in layers if x["backend"] == r["backend"] and x["settings"]["zoom"] == r["settings"]["zoom"]
                    and x["technique"] == "layers-forward")
    for r in layers:
        s = r["settings"]
        w("| %s | %.2f | %d | %.1f | %s | %s | %.2f | %.2fx | %.2f | %d | %s |" % (
            r["backend"], s["zoom"], s["hair_pixels"], s["mean_layers"], r["technique"][len("layers-"):],
            "-" if s["k"] is None else s["k"], r["layers_ms"], reference(r)["layers_ms"] / r["layers_ms"],
            r["rmse_transparent"], r["bytes_per_pixel"], ssim_flip(r)))
    w("")
    for backend in sorted({r["backend"] for r in layers}):
        at8 = [r for r in layers if r["backend"] == backend and r["settings"].get("k") == 8 and r["technique"] == "layers-deferred"]
        if at8:
            worst = max(r["rmse_transparent"] for r in at8)
            speed = min(reference(r)["layers_ms"] / r["layers_ms"] for r in at8)
            w("On %s at k = 8 the deferred variant's RMSE on hair is at most %.2f (S1: %.0f) and it is at least %.2fx "
              "as fast as the forward reference (S1: %s)." % (backend, worst, S1["deferred"], speed, S1["speedup"]))
            w("")
    write_untimed(w, layers)
    w("![RMSE and speed-up against k](layers.png)")
    w("")


def plot_layers(plt, layers, path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), dpi=110)
    layers = [r for r in layers if r["backend"] == layers[0]["backend"]]
    zoom = sorted({r["settings"]["zoom"] for r in layers})[len({r["settings"]["zoom"] for r in layers}) // 2]
    ref = next(r for r in layers if r["settings"]["zoom"] == zoom and r["technique"] == "layers-forward")
    for variant, colour in (("deferred", "tab:blue"), ("tailless", "tab:orange")):
        pts = sorted((r["settings"]["k"], r["rmse_transparent"], ref["layers_ms"] / r["layers_ms"]) for r in layers
                     if r["settings"]["zoom"] == zoom and r["technique"] == "layers-" + variant)
        a.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=variant, color=colour)
        b.plot([p[0] for p in pts], [p[2] for p in pts], marker="o", label=variant, color=colour)
    for variant, colour in (("cheap", "tab:red"), ("wboit", "tab:purple")):
        r = next((r for r in layers if r["settings"]["zoom"] == zoom and r["technique"] == "layers-" + variant), None)
        if r:
            a.axhline(r["rmse_transparent"], color=colour, linestyle="--", label=variant)
            b.axhline(ref["layers_ms"] / r["layers_ms"], color=colour, linestyle="--", label=variant)
    a.axhline(S1["deferred"], color="grey", linestyle=":", label="S1 deferred, k = 8")
    for ax, label in ((a, "RMSE on hair pixels (0-255)"), (b, "speed-up over the forward reference")):
        ax.set_xscale("log", base=2)
        ax.set_xlabel("k")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("k-buffer on hair.json, %s, zoom %.2f" % (layers[0]["backend"], zoom))
    fig.tight_layout()
    fig.savefig(path)


# S2's published figures (TECHNIQUES.md): HD 5670, 3 particle systems, 16x24x16 cells each, six axes:
# forward 9.47 ms, light volumes 1.347 ms (bake 0.311 + render 1.016), 7x; no error reported.
S2 = {"forward": 9.47, "volumes": 1.347, "bake": 0.311, "render": 1.016}


def write_volumes(w, volumes):
    w("## Light volumes: smoke lit from baked 3D textures (S2)")
    w("")
    first = volumes[0]["settings"]
    w("smoke.json: %d particle systems, %d particles, %d lights (directional, point, and three shadowed spot lights, "
      "one behind a crate and one behind green glass), over %d smoke pixels. The reference lights every particle "
      "fragment by every light (Lambert, the spot lights through copies of their shadow maps); light volumes bake "
      "the lights into a grid of N cells a side over each system, on S2's six or four axes, on fourteen (the six "
      "and the cube's corners, a user-supplied set) or as the light's moments (L1, read with Geomerics' non-linear "
      "lobe), stored in RGBA8 as S2 did (bytes a cell: S2's target is 20), and each particle reads it "
      "trilinearly at its centre, once (S2 read it per pixel). "
      "Bake and particle times "
      "are GPU ms as their timestamps give them; added is what the particles add to the frame (the frame less "
      "the frame without them: llvmpipe runs a compute dispatch under the timestamps of the draw before it, so "
      "the bake's own timer misses most of the bake); speed-up is the reference's added time over the volume's; "
      "RMSE (0-255) is against "
      "the reference, on all pixels and on smoke pixels. S2 measured (HD 5670, 16x24x16 cells, six axes): forward "
      "%.2f ms, volumes %.3f ms (bake %.3f + render %.3f), %.1fx; it reported no error."
      % (first["systems"], first["particles"], first["lights"], first["smoke_pixels"], S2["forward"],
         S2["volumes"], S2["bake"], S2["render"], S2["forward"] / S2["volumes"]))
    w("")
    w("| backend | lighting | cells | B/cell | bake ms | particles ms | added ms | speed-up | RMSE | RMSE on smoke | %s |"
      % SSIM_FLIP_HEAD.replace("glass", "smoke"))
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")

    def reference(r):
        return next(x for x in volumes if x["backend"] == r["backend"] and x["technique"] == "volumes-forward")

    def speed(r):  # None where the frames' noise left nothing added
        return reference(r)["lighting_ms"] / r["lighting_ms"] if r["lighting_ms"] > 0 else None

    def speedup(r):
        return "-" if speed(r) is None else "%.2fx" % speed(r)
    for r in volumes:
        s = r["settings"]
        w("| %s | %s | %s | %s | %.2f | %.2f | %.2f | %s | %.2f | %.2f | %s |" % (
            r["backend"], r["technique"][len("volumes-"):], "-" if s["cells"] is None else s["cells"],
            "-" if s["bytes_per_cell"] is None else s["bytes_per_cell"], r["bake_ms"],
            r["particles_ms"], r["lighting_ms"], speedup(r), r["rmse"], r["rmse_transparent"], ssim_flip(r)))
    w("")
    for backend in sorted({r["backend"] for r in volumes}):
        rows = [r for r in volumes if r["backend"] == backend and r["technique"] != "volumes-forward"]
        best = min(rows, key=lambda r: r["rmse"])
        fastest = max(rows, key=lambda r: speed(r) or 0.0)
        w("On %s the most accurate volume is %s at %d cells (RMSE %.2f, %s the reference's speed); the fastest is "
          "%s at %d cells (%s, RMSE %.2f)." % (
              backend, best["technique"][len("volumes-"):], best["settings"]["cells"], best["rmse"], speedup(best),
              fastest["technique"][len("volumes-"):], fastest["settings"]["cells"], speedup(fastest), fastest["rmse"]))
        w("")
    write_untimed(w, volumes)
    w("![bake and particle time and RMSE against grid size](volumes.png)")
    w("")


def plot_volumes(plt, volumes, path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), dpi=110)
    volumes = [r for r in volumes if r["backend"] == volumes[0]["backend"]]
    ref = next(r for r in volumes if r["technique"] == "volumes-forward")
    for lighting, colour in (("six-axes", "tab:blue"), ("four-axes", "tab:orange"), ("fourteen-axes", "tab:green"),
                             ("moments", "tab:purple")):
        pts = sorted((r["settings"]["cells"], r["rmse"], r["lighting_ms"]) for r in volumes
                     if r["technique"] == "volumes-" + lighting)
        if pts:
            a.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=lighting, color=colour)
            b.plot([p[0] for p in pts], [p[2] for p in pts], marker="o", label=lighting + " (added to the frame)", color=colour)
    b.axhline(ref["lighting_ms"], color="tab:red", linestyle="--", label="forward reference")
    for ax, label in ((a, "RMSE against the reference (0-255)"), (b, "GPU ms")):
        ax.set_xlabel("cells a side")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Light volumes on smoke.json, %s" % volumes[0]["backend"])
    fig.tight_layout()
    fig.savefig(path)


def write_post(w, post):
    w("## Post-processing and anti-aliasing (S3)")
    w("")
    first = post[0]["settings"]
    w("glass_room with %d spot lights at %dx%d. Each effect's time is its passes' GPU ms in a chain of all six "
      "(anti-aliasing, bloom, depth of field, blur, greyscale, sepia). The anti-aliasing is measured against depth "
      "peeling rendered at twice the size and box-filtered down (an anti-aliased reference) over the glass edges "
      "(pixels whose 3x3 neighbourhood in the peeled first layer holds both glass and not: %d pixels): S3's plain "
      "edge detection, and the one that compares the surfaces in front, aware of the interlace predicate."
      % (first["lights"], first["width"], first["height"],
         next(r["settings"]["edge_pixels"] for r in post if r["technique"].startswith("aa-"))))
    w("")
    w("| backend | effect | ms |")
    w("|---|---|---|")
    for r in post:
        if r["technique"].startswith("post-"):
            w("| %s | %s | %.2f |" % (r["backend"], r["technique"][len("post-"):], r["post_ms"]))
    w("")
    w("| backend | frame | anti-aliasing ms | RMSE at glass edges | RMSE, all pixels | %s |"
      % SSIM_FLIP_HEAD.replace("on glass", "at glass edges"))
    w("|---|---|---|---|---|---|---|---|---|")
    for r in post:
        if r["technique"].startswith("aa-"):
            w("| %s | %s | %.2f | %.2f | %.2f | %s |" % (r["backend"], r["technique"][len("aa-"):], r["post_ms"],
                                                        r["rmse_transparent"], r["rmse"], ssim_flip(r)))
    w("")
    for backend in sorted({r["backend"] for r in post}):
        by = {r["technique"]: r for r in post if r["backend"] == backend}
        if "aa-interlaced" in by and "aa-interlaced+aa-interlace" in by:
            a, b, c = by["aa-interlaced"], by["aa-interlaced+aa"], by["aa-interlaced+aa-interlace"]
            w("On %s the interlace-aware anti-aliasing changes the interlaced frame's error at glass edges from %.2f "
              "to %.2f (%s); S3's plain one, which takes the interlaced rows for edges, gives %.2f." % (
                  backend, a["rmse_transparent"], c["rmse_transparent"],
                  pct(c["rmse_transparent"], a["rmse_transparent"]), b["rmse_transparent"]))
            w("")
    w("![effect times and the anti-aliasing's error at glass edges](post.png)")
    w("")


def plot_post(plt, post, path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), dpi=110)
    post = [r for r in post if r["backend"] == post[0]["backend"]]
    effects = [r for r in post if r["technique"].startswith("post-")]
    a.bar([r["technique"][len("post-"):] for r in effects], [r["post_ms"] for r in effects], color="tab:blue")
    a.set_ylabel("GPU ms")
    a.set_title("time per effect")
    aa = [r for r in post if r["technique"].startswith("aa-")]
    b.bar([r["technique"][len("aa-"):] for r in aa], [r["rmse_transparent"] for r in aa], color="tab:orange")
    b.set_ylabel("RMSE at glass edges (0-255)")
    b.set_title("against 2x peeling, box-filtered")
    b.tick_params(axis="x", labelrotation=20, labelsize=8)
    fig.suptitle("Post-processing on glass_room, %s" % post[0]["backend"])
    fig.tight_layout()
    fig.savefig(path)


def write_sweep(w, sweep):
    w("## Beyond the thesis: interlace predicates, edge-aware reconstruction, a compact layout")
    w("")
    first = sweep[0]["settings"]
    w("glass_room with %d spot lights, transparent shadows and refraction, %dx%d. Each interlace predicate with "
      "the thesis's partner fetch and with the edge-aware reconstruction (the other layer averaged from its "
      "samples around the pixel that show the same surface), against deferred depth peeling at the same settings. "
      "Layouts: Table 3.1's (16 bytes a pixel, 20 with the light buffer) and the compact one (8, 12 with the light "
      "buffer: octahedral normals, depth from the depth attachment). Targets: RMSE on glass at most 3, at least "
      "1.6x faster than peeling, at most 12 bytes a pixel." % (first["lights"], first["width"], first["height"]))
    w("")
    w("| backend | technique | predicate | reconstruction | layout | ms | vs peeling | bytes/px | RMSE | RMSE on glass | PSNR "
      "| %s |" % SSIM_FLIP_HEAD)
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in sweep:
        s = r["settings"]
        w("| %s | %s | %s | %s | %s | %.2f | %.2fx | %d | %.2f | %.2f | %s | %s |" % (
            r["backend"], r["technique"].split("-")[0], s["predicate"] or "-", s["reconstruction"] or "-", s["layout"], r["frame_ms"],
            r["peeling_ms"] / r["frame_ms"], r["bytes_per_pixel"], r["rmse"], r["rmse_transparent"],
            "-" if r["psnr"] is None else "%.1f" % r["psnr"], ssim_flip(r)))
    w("")
    for backend in sorted({r["backend"] for r in sweep}):
        rows = [r for r in sweep if r["backend"] == backend and r["technique"] != "peeling"]
        thesis = next(r for r in rows if r["technique"] == "interlaced-rows-partner-thesis")
        best = min(rows, key=lambda r: r["rmse_transparent"])
        w("On %s the closest to peeling on glass is %s with %s reconstruction in the %s layout: RMSE on glass %.2f "
          "(the thesis's rows, partner fetch and Table 3.1: %.2f, %s), %.2fx peeling's speed (the thesis's %.2fx), %d "
          "bytes a pixel (the thesis's %d)." % (
              backend, best["settings"]["predicate"], best["settings"]["reconstruction"], best["settings"]["layout"],
              best["rmse_transparent"], thesis["rmse_transparent"], pct(best["rmse_transparent"], thesis["rmse_transparent"]),
              best["peeling_ms"] / best["frame_ms"], thesis["peeling_ms"] / thesis["frame_ms"], best["bytes_per_pixel"],
              thesis["bytes_per_pixel"]))
        w("")
    w("![RMSE on glass against frame time](reconstruction.png)")
    w("")


def timed_share(pass_ms, frame_ms):
    """What a frame's timers hold of the frame's own time: near 1 where each pass's work lies between its
    timestamps; far from it where a driver runs work outside them (then per-pass times are not to be trusted)."""
    return sum(pass_ms.values()) / frame_ms if frame_ms > 0 else None


def trusted(share):
    return share is not None and 0.9 <= share <= 1.1


def pair_share(r):
    """Of a pair's two sides, the share farther from 1."""
    shares = [timed_share(r[side + "_pass_ms"], r[side + "_frame_ms"]) for side in ("a", "b")]
    return None if None in shares else max(shares, key=lambda s: abs(s - 1.0))


def bound(r):
    """The best ratio the machine allows, from the pair's own per-pass medians and copy limits.

    The compared passes are each side's timers (every timer where none are named). For a speed-up (B/A at
    least x): B's passes as measured over A's, each pass of A that B does not run alike at the time of a copy
    of its bytes, or the upper end of the interval of the technique's floor, timed in pairs beside it (or of
    the pair's own, where that is higher), where that is lower. For a cost (B/A at most x): A's passes as
    measured plus, for every pass, the copy time of the bytes B moves beyond A's, which B cannot do without."""
    if r["target"] is None:
        return None
    a_timers = r["timers"]["a"] or list(r["a_pass_ms"])
    b_timers = r["timers"]["b"] or list(r["b_pass_ms"])
    a_ms = sum(r["a_pass_ms"][t] for t in a_timers)
    b_ms = sum(r["b_pass_ms"][t] for t in b_timers)
    if a_ms <= 0:
        return None
    if "at_least" in r["target"]:
        best = sum(r["a_pass_ms"][t] if t in r["alike"] else r["a_limit_ms"][t] for t in a_timers)
        if best <= 0:
            return None
        if "floor" not in r:
            return b_ms / best
        # A floor below what the pair itself reached is noise (few pairs, a small frame): then the pair's
        # own upper end is the most the measurement shows.
        return min(b_ms / best, max(r["floor"]["high"], r["high"]))
    extra = sum(max(0.0, r["b_limit_ms"][t] - r["a_limit_ms"].get(t, 0.0)) for t in b_timers)
    return (a_ms + extra) / a_ms


def met(r, limit=None):
    """Whether the ratio's whole 95% interval meets its target: yes, no, or unclear where it straddles it;
    "bounded" where it does not and the machine's limit (bound) rules the target out. A target with an error
    bound (rmse_at_most) is missed where the RMSE exceeds it, whatever the time; one with a memory bound
    (bytes_per_cell_at_most) where the bytes a cell do."""
    if r["target"] is None:
        return "-"
    if r["target"].get("rmse_at_most") is not None and r["rmse"] > r["target"]["rmse_at_most"]:
        return "no (RMSE)"
    if r["target"].get("bytes_per_cell_at_most") is not None and r["bytes_per_cell"] > r["target"]["bytes_per_cell_at_most"]:
        return "no (bytes)"
    if "at_least" in r["target"]:
        want = r["target"]["at_least"]
        verdict = "yes" if r["low"] >= want else "no" if r["high"] < want else "unclear"
        out_of_reach = limit is not None and limit < want
    else:
        want = r["target"]["at_most"]
        verdict = "yes" if r["high"] <= want else "no" if r["low"] > want else "unclear"
        out_of_reach = limit is not None and limit > want
    return "bounded" if verdict != "yes" and out_of_reach else verdict


def write_paired(w, rows):
    w("## The targets, timed in pairs")
    w("")
    w("Each ratio is B's median frame over A's (for example peeling's time over interlacing's), the two "
      "configurations' frames rendered alternately (A B, B A, ...) after two warm-up pairs, so that what else "
      "the machine does slows both alike; the interval is 95%%, from %d bootstrap resamples of the pairs, "
      "and pairs are added (up to a maximum) until it is at most 3%% of the ratio wide. A "
      "target is met when the whole interval meets it. The bound is the best ratio this machine allows, from "
      "the same frames' per-pass medians and each pass's copy limit (next section): for a speed-up, B over A "
      "with every pass of A that B does not run alike (on glass_room: that moves other bytes) at the speed of a "
      "copy of its bytes; for a cost, A plus the copy time of the bytes B moves beyond A's. \"bounded\": the "
      "target is missed and lies beyond the bound." % 2000)
    w("")
    w("The k-buffer (hair.json, S1) is timed on the passes S1 compares, capture and resolve, its capture alike "
      "(one program for every list variant), and bounded by its floor: S1's tailless variant, which shades no "
      "tail at all, timed in pairs against the same reference (the upper end of its interval, shown below the table, or of "
      "the pair's own where that is higher); "
      "the light volumes (smoke.json, S2) on what the particles add to a "
      "frame, each frame less a frame of the same settings without particles (the bake's own timer misses the "
      "compute work llvmpipe runs under the draw before it), no pass alike. Their target holds only at the "
      "RMSE beside it (hair: on hair pixels against the forward reference; smoke: on all pixels, the light "
      "volume being the setting of the sweep fastest at RMSE at most 5, or the most accurate where none is).")
    w("")
    w("The timers column is what the passes' timestamps hold of the frame's time (of A or B, the farther from "
      "100%): where it is outside 90-110%, the driver runs work outside the passes' timestamps, so no bound is "
      "drawn from them, and a ratio of named passes is \"untrusted\".")
    w("")
    w("| comparison | scene | lights | pairs | A ms | B ms | ratio | 95% interval | width | RMSE | timers | target | bound | met |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        t = r["target"]
        target = "-" if t is None else (">= %.2f" % t["at_least"] if "at_least" in t else "<= %.2f" % t["at_most"])
        if t is not None and t.get("rmse_at_most") is not None:
            target += " at RMSE <= %g" % t["rmse_at_most"]
        if t is not None and t.get("bytes_per_cell_at_most") is not None:
            target += ", <= %g B a cell" % t["bytes_per_cell_at_most"]
        settings = "" if r["scene"] == "glass_room_paired" else " (A: %s)" % ", ".join(
            [r["a"]["technique"]] + ["%s %s" % kv for kv in r["a"].items() if kv[0] != "technique"])
        share = pair_share(r)
        limit = bound(r) if trusted(share) else None
        verdict = "untrusted" if r["timers"]["a"] and not trusted(share) and t is not None else met(r, limit)
        w("| %s%s | %s | %d | %d | %.2f | %.2f | %.3f | [%.3f, %.3f] | %.1f%% | %s | %s | %s | %s | %s |" % (
            r["technique"], settings, r["scene"][:-len("_paired")], r["settings"]["lights"], r["settings"]["frames"],
            r["a_ms"], r["b_ms"], r["ratio"], r["low"], r["high"], 100.0 * r["spread"],
            "-" if r.get("rmse") is None else "%.2f" % r["rmse"], "-" if share is None else "%.0f%%" % (100.0 * share),
            target, "-" if limit is None else "%.3f" % limit, verdict))
    w("")
    for r in rows:
        if "floor" in r:
            f = r["floor"]
            w("Floor of \"%s\": the same pair with A as %s, %.3f [%.3f, %.3f]." % (
                r["technique"], f["technique"], f["ratio"], f["low"], f["high"]))
            w("")


def write_shadow_kinds(w, paired, soft):
    """Beside Table 4.3: each light kind's transparent shadow against its opaque one, hard and soft, in time
    (paired rows) and the soft shadows' error against a supersampled reference (scene glass_room_shadows)."""
    kinds = [r for r in paired if r["technique"].startswith("transparent / opaque shadows")
             and (", " in r["technique"] or r["settings"]["lights"] == 2)]
    if not kinds and not soft:
        return
    w("### Beyond the thesis: every light kind, and soft shadows")
    w("")
    w("The thesis's transparent shadows are a spot light's, with hard edges. A directional light's map is "
      "orthographic over the scene's bounds; a point light's is a cube, six 90-degree faces drawn into tiles of "
      "the one map; soft shadows average Eq. 3.1 over 5 x 5 texels, each with its own interlace partner. Ratios "
      "timed in pairs on glass_room lit by 2 of its spot lights, by a sun alone and by a lamp alone (The "
      "targets, timed in pairs); no source sets a target for them.")
    w("")
    w("| pair | lights | ratio | 95% interval |")
    w("|---|---|---|---|")
    for r in kinds + [r for r in paired if r["technique"].startswith("filtered ")]:
        w("| %s | %d | %.3f | [%.3f, %.3f] |" % (r["technique"], r["settings"]["lights"], r["ratio"], r["low"], r["high"]))
    w("")
    if not soft:
        return
    w("The error of hard and filtered shadows against a supersampled reference: the same light's map three "
      "times as fine, filtered over the same width of the scene (15 x 15 texels), transparent shadows and "
      "refraction on. The penumbra is the pixels the reference's filter changes (against its own fine map "
      "unfiltered) by more than one step; RMSE over 0-255 channel values.")
    w("")
    w("| backend | light | filter | ms | RMSE | penumbra pixels | penumbra RMSE | penumbra FLIP |")
    w("|---|---|---|---|---|---|---|---|")
    for r in soft:
        st = r["settings"]
        f = st["shadow_filter"]
        w("| %s | %s | %s | %.2f | %.2f | %d | %.2f | %.3f |" % (
            r["backend"], st["light"], "hard" if f == 1 else "%dx%d" % (f, f), ms(r), r["rmse"], st["penumbra_pixels"],
            r["rmse_transparent"], r["flip_transparent"]))
    w("")


def write_limits(w, results):
    """Every pass of the sweep's runs at the most lights, with transparent shadows, against a copy of its bytes."""
    most = max(r["settings"]["lights"] for r in results)
    runs = [r for r in results if r["scene"] == "glass_room" and r["settings"]["lights"] == most and "limit_ms" in r
            and r["settings"]["shadows"] == "transparent" and r["settings"]["refraction"] and not r["settings"]["forced"]]
    if not runs:
        return
    w("## Each pass against a copy of its bytes")
    w("")
    w("A pass's bytes are half of what the targets it reads and writes hold together (the scene's meshes count "
      "nothing), and its limit is the GPU time of a copy of that many bytes between two RGBA32F images on the "
      "same device, measured in this run (the median of five copies): a pass cannot move its bytes faster. "
      "The multiple is how far each pass is from it; a timer sums its passes (every light's). glass_room, "
      "%d lights, transparent shadows." % most)
    w("")
    w("| technique | pass | ms | MB | copy ms | multiple |")
    w("|---|---|---|---|---|---|")
    for r in runs:
        for timer, t in sorted(r["pass_ms"].items(), key=lambda kv: -kv[1]):
            limit = r["limit_ms"].get(timer, 0.0)
            w("| %s | %s | %.2f | %.2f | %.3f | %s |" % (
                r["technique"], timer, t, r["pass_bytes"].get(timer, 0) / 1e6, limit,
                "-" if limit <= 0 else "%.0fx" % (t / limit)))
    w("")


def write_specular(w, rows):
    w("## Beyond the thesis: RGB specular in the light buffer")
    w("")
    first = rows[0]["settings"]
    w("glass_room with %d spot lights coloured around the hue circle (each colour's mean 1), transparent shadows "
      "and refraction, %dx%d. Table 3.2's light buffer keeps one specular number, the mean of the light's RGB, so "
      "a coloured light's highlight comes out white; the RGB one keeps its colour in a second RGBA8 target. The "
      "reference is deferred depth peeling with RGB specular; the last column is the error of white specular alone, "
      "against RGB specular in the same layout." % (first["lights"], first["width"], first["height"]))
    w("")
    w("| backend | specular | layout | ms | vs white | bytes/px | RMSE | RMSE on glass | RMSE against RGB | %s |" % SSIM_FLIP_HEAD)
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        s = r["settings"]
        white = next(x for x in rows if x["backend"] == r["backend"] and x["settings"]["layout"] == s["layout"]
                     and x["settings"]["specular"] == "white")
        w("| %s | %s | %s | %.2f | %+.1f%% (spread %.2f ms) | %d | %.2f | %.2f | %.2f | %s |" % (
            r["backend"], s["specular"], s["layout"], r["frame_ms"], 100.0 * (r["frame_ms"] / white["frame_ms"] - 1.0),
            r["frame_ms_spread"], r["bytes_per_pixel"], r["rmse"], r["rmse_transparent"], r["rmse_against_rgb"], ssim_flip(r)))
    w("")


def write_gltf(w, rows):
    """glass_shelf.gltf: each technique against depth peeling, on each backend."""
    first = rows[0]["settings"]
    w("## A glTF scene: glass_shelf.gltf")
    w("")
    w("Glass as glTF describes it (examples/scenes/make_glass_shelf.py: KHR_materials_transmission panes, "
      "solid glass with KHR_materials_volume tints, %d triangles, %d punctual lights, each casting transparent "
      "shadows), %dx%d, refraction on. The reference is deferred depth peeling; the temporal row is the third "
      "frame of a still camera. The -rough rows blur what rough glass refracts (--rough-refraction on: the "
      "frosted pane, roughness 0.6) and are compared with peeling that blurs alike. Times are one run's median "
      "frame; peeling's over interlacing's, and the blur's cost (rough over sharp), timed in pairs with their "
      "intervals, are the glass_shelf rows of The targets, timed in pairs."
      % (first["triangles"], first["lights"], first["width"], first["height"]))
    w("")
    w("| backend | technique | ms | bytes/px | RMSE | RMSE on glass | %s |" % SSIM_FLIP_HEAD)
    w("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        w("| %s | %s | %.2f | %d | %.2f | %.2f | %s |" % (
            r["backend"], r["technique"], r["frame_ms"], r["bytes_per_pixel"], r["rmse"], r["rmse_transparent"], ssim_flip(r)))
    w("")


def write_around_glass(w, rows):
    """Hair and smoke on both sides of glass: each technique against depth peeling, on each backend."""
    first = rows[0]["settings"]
    w("## Glass, hair and smoke in one frame, in depth order")
    w("")
    w("hair_panes.json (hair.json with a blue pane in front of the hair and an amber one behind it) and "
      "glass_room_smoke.json (glass_room with a smoke column behind its front left pane and one in front of its "
      "centre pane; its first spot lights, as the thesis's tables), %dx%d, transparent shadows, refraction on. "
      "The k-buffer's hair and the particles are drawn before the compose into a layer behind each pixel's glass "
      "and one in front of it (docs/integration.md, \"Hair and particles around glass\"); peeling does the same "
      "with its two layers and is one reference; the exact reference (every transparent fragment of glass, hair "
      "and smoke sorted per pixel and shaded fully, without refraction) is the other. Times are one run's median "
      "frame; the exact reference's is one frame's." % (first["width"], first["height"]))
    w("")
    w("| backend | scene | technique | ms | vs peeling | bytes/px | RMSE | RMSE on glass | RMSE vs exact | on glass vs exact | %s |"
      % SSIM_FLIP_HEAD)
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        w("| %s | %s | %s | %.2f | %.2fx | %d | %.2f | %.2f | %s | %s | %s |" % (
            r["backend"], r["scene"], r["technique"], r["frame_ms"], r["frame_ms"] / r["peeling_ms"], r["bytes_per_pixel"],
            r["rmse"], r["rmse_transparent"], exact(r), exact(r, "rmse_transparent"), ssim_flip(r)))
    w("")


def write_paths(w, paths, paired):
    """Temporal interlacing along camera paths, each method's frames against peeling's of the same frame;
    beside the temporal method's times, the thesis's interlacing against peeling at the paths' light count,
    timed in pairs (the targets' table), where that backend has the pair."""
    first = paths[0]["settings"]
    w("")
    w("## Temporal interlacing along camera paths")
    w("")
    w("glass_room with %d lights, %dx%d, %d frames a path drawn by one renderer: a still camera, a slow orbit (0.5 "
      "degrees a frame), a fast pan (2 degrees of yaw a frame), a dolly through the panes (4%% of the distance a "
      "frame), and a pane moving 2 cm a frame under a still camera. Methods: the thesis's (partner fetch, Table "
      "3.1's layout), spatial (edge-aware reconstruction, compact layout), temporal (the rows that keep glass "
      "alternate every frame; the other layer from the previous frame where it is still on the pixel's ray, else "
      "the partner's; compact layout) and depth peeling in both layouts. Every frame after the first is compared with "
      "peeling's of the same frame in the method's layout on the glass peeling's first layer holds: the mean and "
      "the worst frame; the column after them is against Table 3.1's peeling (what the compact layout's normals "
      "add). Frame change: RMSE on "
      "glass between consecutive frames of the method from the second frame on (on the still path, its flicker "
      "once the temporal method has a history; peeling's is 0 there). "
      "FLIP vs exact: the mean FLIP on glass against the exact reference of each frame (`--technique reference`, "
      "which does not refract; \"overflow\" where its lists overflowed). "
      "Times are the median frame after the first; \"vs peeling\" is that over Table 3.1 peeling's median, "
      "and for the temporal method the ratio of its frames to peeling's timed in pairs along the path, with its "
      "95%% interval. Targets (temporal): RMSE on glass at most 2, at most 0.625x peeling's time, at most 24 bytes a pixel (the "
      "thesis's 20 and 4). The last frame of each path, cropped where the glass is (thesis, spatial, temporal, "
      "peeling): temporal_<backend>.png." % (first["lights"], first["width"], first["height"], first["frames"]))
    w("")
    w("| backend | path | method | RMSE on glass | worst frame | against Table 3.1 peeling | SSIM on glass | FLIP on glass "
      "| worst FLIP | FLIP vs exact | frame change | ms | vs peeling | bytes/px |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")

    def flip_exact(r):
        if r["flip_transparent_against_exact"] is None:
            return "overflow (%d)" % r["exact_overflow"]
        return "%.4f" % r["flip_transparent_against_exact"]

    def frame_change(r):
        return "-" if r["frame_change_transparent"] is None else "%.2f" % r["frame_change_transparent"]

    def against_peeling(r):
        p = r["paired_against_peeling"]
        if p is None:
            return "%.2fx" % (r["frame_ms"] / r["peeling_ms"])
        return "%.2fx [%.2f, %.2f] in pairs" % (p["ratio"], p["low"], p["high"])

    for r in paths:
        s = r["settings"]
        w("| %s | %s | %s | %.2f | %.2f | %.2f | %.4f | %.4f | %.4f | %s | %s | %.2f | %s | %d |" % (
            r["backend"], s["path"], s["method"], r["rmse_transparent"], r["worst_rmse_transparent"],
            r["rmse_transparent_against_thesis_peeling"], r["ssim_transparent"], r["flip_transparent"],
            r["worst_flip_transparent"], flip_exact(r), frame_change(r), r["frame_ms"],
            against_peeling(r), r["bytes_per_pixel"]))
    w("")
    for backend in sorted({r["backend"] for r in paths}):
        temporal = [r for r in paths if r["backend"] == backend and r["settings"]["method"] == "temporal"]
        met = [r["settings"]["path"] for r in temporal if r["rmse_transparent"] <= 2.0 and r["worst_rmse_transparent"] <= 2.0]
        fast = [r["settings"]["path"] for r in temporal if r["paired_against_peeling"]["high"] <= 0.625]
        w("On %s the temporal method's RMSE on glass is at most 2 on every frame of %s; timed in pairs it takes "
          "%.2fx to %.2fx peeling's time, at most 0.625x (the interval's upper end included) on %s; %d bytes a pixel." % (
              backend, ", ".join(met) if met else "no path", min(r["paired_against_peeling"]["ratio"] for r in temporal),
              max(r["paired_against_peeling"]["ratio"] for r in temporal), ", ".join(fast) if fast else "no path",
              temporal[0]["bytes_per_pixel"]))
        peeled = {r["settings"]["path"]: r for r in paths
                  if r["backend"] == backend and r["settings"]["method"] == "peeling"}
        near = [r["settings"]["path"] for r in temporal if r["flip_transparent_against_exact"] is not None
                and peeled[r["settings"]["path"]]["flip_transparent_against_exact"] is not None
                and r["flip_transparent_against_exact"] <= 1.1 * peeled[r["settings"]["path"]]["flip_transparent_against_exact"]]
        w("Its FLIP on glass against the exact reference is within 10%% of peeling's own on %s." % (
            ", ".join(near) if near else "no path"))
        still = [r for r in temporal if r["settings"]["path"] == "still" and r["frame_change_transparent"] is not None]
        if still and "still" in peeled:
            w("On the still camera its glass changes by RMSE %.2f from frame to frame once it has a history (flicker; "
              "peeling's %.2f), and every frame from the second is within RMSE %.2f of peeling's." % (
                  still[0]["frame_change_transparent"], peeled["still"]["frame_change_transparent"],
                  still[0]["worst_rmse_transparent"]))
        thesis = [r for r in paired if r["backend"] == backend and r["settings"]["lights"] == first["lights"]
                  and r["technique"] == "peeling / interlaced, transparent shadows" and r["scene"] == "glass_room_paired"]
        if thesis:
            r = thesis[0]
            w("For comparison, the thesis's interlacing takes %.2fx [%.2f, %.2f] of peeling's time at %d lights with "
              "transparent shadows, timed in pairs (the targets' table); the temporal method runs the same shadow "
              "and light passes." % (
                  1.0 / r["ratio"], 1.0 / r["high"], 1.0 / r["low"], first["lights"]))
        w("![the last frame of each path on %s](temporal_%s.png)" % (backend, backend))
        w("")


def plot_sweep(plt, sweep, path):
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=110)
    sweep = [r for r in sweep if r["backend"] == sweep[0]["backend"]]
    for r in sweep:
        s = r["settings"]
        label = "peeling" if r["technique"] == "peeling" else "%s, %s, %s" % (s["predicate"], s["reconstruction"], s["layout"])
        ax.scatter([r["frame_ms"]], [r["rmse_transparent"]], s=28, marker="s" if s["layout"] == "compact" else "o",
                   color="tab:green" if r["technique"] == "peeling" else
                   ("tab:blue" if s["reconstruction"] == "edge-aware" else "tab:orange"))
        ax.annotate(label, (r["frame_ms"], r["rmse_transparent"]), fontsize=7, xytext=(4, 2), textcoords="offset points")
    ax.axhline(3.0, color="grey", linestyle=":", label="target: RMSE on glass 3")
    ax.set_xlabel("frame time (GPU ms)")
    ax.set_ylabel("RMSE on glass against peeling (0-255)")
    ax.set_title("Predicates and reconstruction, glass_room, %s" % sweep[0]["backend"])
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    main()
