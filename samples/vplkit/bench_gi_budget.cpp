// The budget chooser against the bench's measurements (bench_gi_budget.hpp).

#include "bench_gi_budget.hpp"

#include "bench_gi_measure.hpp"

#include "stats_json.hpp"

#include "vplkit/budget.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

namespace vplkit::cli {

namespace {

// "rtslc 64 spp half svgf, 1024 vpls"
std::string short_config(const BudgetConfig& c) {
    std::string s = std::string(gi_method_name(c.method)) + " " + std::to_string(c.spp) + " spp";
    if (c.half_resolution) s += " half";
    if (c.denoise == DenoiseMode::svgf) s += " svgf";
    return s + ", " + std::to_string(c.vpls) + " vpls";
}

// The configuration a comparable point ran.
BudgetConfig config_of(const BenchPoint& p, const RenderSettings& base, VplSource source) {
    return BudgetConfig{
        find_gi_method(p.method)->method, p.spp,  p.half, p.denoised ? DenoiseMode::svgf : DenoiseMode::off,
        vpl_count_knob(base, source),     p.block};
}

bool same_config(const BudgetConfig& a, const BudgetConfig& b) {
    return a.method == b.method && a.spp == b.spp && a.half_resolution == b.half_resolution && a.denoise == b.denoise &&
           a.vpls == b.vpls && (!gi_method(a.method).blocks || a.block_size == b.block_size);
}

std::string fixed2(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", v);
    return text;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// "sst 0.0123, 0.045; rtslc ...": svgf's effect per method as measured.
std::string svgf_effects(const ErrorModel& error) {
    std::string out;
    for (const NoiseMeasurement& m : error.sampling) {
        if (!m.svgf) continue;
        char text[96];
        std::snprintf(text, sizeof text, "%s%s %.4f, %.3f", out.empty() ? "" : "; ", gi_method_name(m.method),
                      std::sqrt(m.svgf->floor_variance), m.svgf->noise_share);
        out += text;
    }
    return out.empty() ? "not measured" : out;
}

}  // namespace

bool time_ok(const BudgetCheckRow& r) {
    return r.measured_ms <= kBudgetTimeSlack * r.budget_ms;
}

bool rmse_ok(const BudgetCheckRow& r) {
    return !r.best.empty() && r.measured_rmse <= kBudgetRmseSlack * r.best_rmse;
}

void print_budget_check(const BenchRun& run) {
    std::printf("budget chooser: %s\n", run.budget_note.c_str());
    for (const BudgetCheckRow& r : run.budget_check) {
        std::printf("  %s %3.0f%%: B %.1f ms: %s%s, predicted %.1f ms; measured %.1f ms (%.2f B, %s), RMSE %.4f",
                    r.scale == 1.0 ? "calibrated" : ("x" + fixed2(r.scale)).c_str(), 100.0 * r.fraction, r.budget_ms,
                    r.chosen.c_str(), r.over_budget ? " (nothing predicted within B)" : "", r.predicted_ms,
                    r.measured_ms, r.measured_ms / r.budget_ms, time_ok(r) ? "ok" : "over 1.15 B", r.measured_rmse);
        if (r.best.empty()) {
            std::printf("; nothing measured within B\n");
        } else {
            std::printf(" (%.2fx the best within B, %s: %s, %.4f)\n", r.measured_rmse / r.best_rmse,
                        rmse_ok(r) ? "ok" : "over 1.25x", r.best.c_str(), r.best_rmse);
        }
    }
}

std::string budget_check_markdown(const BenchRun& run) {
    std::ostringstream md;
    md.setf(std::ios::fixed);
    md << "\n## The budget chooser (`--budget-ms`)\n\n"
       << "For budgets B across the time range of the points in the chooser's space (sst, rtslc, hybrid at block 8; "
          "full or half resolution, raw or svgf), what `--budget-ms B` chooses, measured like a point, against the "
          "best "
          "point measured within B (the sweep's and the choices'). Criteria: measured time <= "
       << kBudgetTimeSlack << " B, RMSE <= " << kBudgetRmseSlack << "x the best within B. " << run.budget_note
       << ".\n\n";
    if (run.budget_check.empty()) return md.str();
    md << "| model | B (% of range) | B ms | chosen | predicted ms | measured ms (/ B) | RMSE | best within B | its ms "
          "| its "
          "RMSE | RMSE / best | ok |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const BudgetCheckRow& r : run.budget_check) {
        md.precision(2);
        md << "| " << (r.scale == 1.0 ? std::string("calibrated") : "times x" + fixed2(r.scale)) << " | ";
        md.precision(0);
        md << 100.0 * r.fraction << "% | ";
        md.precision(1);
        md << r.budget_ms << " | " << r.chosen << (r.over_budget ? " (none predicted within B)" : "") << " | "
           << r.predicted_ms << " | " << r.measured_ms;
        md.precision(2);
        md << " (" << r.measured_ms / r.budget_ms << ") | ";
        md.precision(4);
        md << r.measured_rmse << " | ";
        if (r.best.empty()) {
            md << "none | | | | ";
        } else {
            md << r.best << " | ";
            md.precision(1);
            md << r.best_ms << " | ";
            md.precision(4);
            md << r.best_rmse << " | ";
            md.precision(2);
            md << r.measured_rmse / r.best_rmse << " | ";
        }
        md << (time_ok(r) && rmse_ok(r) ? "yes" : !time_ok(r) ? "no: time" : "no: RMSE") << " |\n";
    }
    md << "\n![chosen vs best RMSE](budget_rmse.png) ![chosen time vs budget](budget_time.png)\n";
    return md.str();
}

nlohmann::ordered_json budget_check_json(const BenchRun& run) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const BudgetCheckRow& r : run.budget_check) {
        rows.push_back({{"scale", json_number(r.scale)},
                        {"fraction", json_number(r.fraction)},
                        {"budget_ms", json_number(r.budget_ms)},
                        {"chosen", r.chosen},
                        {"predicted_ms", json_number(r.predicted_ms)},
                        {"predicted_rmse", json_number(r.predicted_rmse)},
                        {"over_budget", r.over_budget},
                        {"measured_ms", json_number(r.measured_ms)},
                        {"measured_rmse", json_number(r.measured_rmse)},
                        {"best", r.best},
                        {"best_ms", r.best.empty() ? nlohmann::ordered_json() : json_number(r.best_ms)},
                        {"best_rmse", r.best.empty() ? nlohmann::ordered_json() : json_number(r.best_rmse)}});
    }
    return rows;
}

bool in_budget_space(const BenchPoint& p) {
    const GiMethodInfo* info = find_gi_method(p.method);  // null for a variant's curve (hybrid-lightcuts)
    const bool method = info && info->budget;
    const bool sweep = p.sweep == "spp" || p.sweep == "resolution" || p.sweep == "denoise";
    return method && sweep && p.block == 8 && p.interleave == 1 && p.mock_cuts && p.frames > 0;
}

void check_budget_chooser(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                          const BudgetCheckInputs& in, BenchRun& run) {
    std::vector<const BenchPoint*> comparable;
    for (const BenchPoint& p : run.points) {
        if (in_budget_space(p)) comparable.push_back(&p);
    }
    if (comparable.size() < 2) {
        run.budget_note = "no check of the budget chooser: fewer than two points of its space were measured";
        return;
    }
    double lo = comparable.front()->frame_ms, hi = lo;
    for (const BenchPoint* p : comparable) {
        lo = std::min(lo, p->frame_ms);
        hi = std::max(hi, p->frame_ms);
    }
    const RenderSettings& base = *in.base;
    const VplSource source = plan_frame(scene, base, "bench").vpl_source;
    BudgetCalibrationOptions options;
    options.cache_dir = in.cache_dir;
    options.scene_id = in.scene_id;
    options.progress = [](uint32_t done, uint32_t total) {
        std::fprintf(stderr, "[bench] budget calibration frame %u/%u\n", done, total);
    };
    const BudgetSpace space = default_budget_space(base, source);
    const BudgetCalibration calibration =
        calibrate_budget(renderer, device, scene, scene.camera(), base, space, options);
    const std::vector<BudgetCandidate> candidates = budget_candidates(calibration.model, space, scene, base);
    if (candidates.empty()) {
        run.budget_note = "no check of the budget chooser: the calibration predicts no configuration";
        return;
    }

    // How the model's times compare with this run's measured ones (the machine's load moves both).
    std::vector<double> ratios;
    for (const BenchPoint* p : comparable) {
        const BudgetConfig c = config_of(*p, base, source);
        for (const BudgetCandidate& k : candidates) {
            if (same_config(k.config, c) && k.predicted_ms > 0) ratios.push_back(p->frame_ms / k.predicted_ms);
        }
    }
    const std::string made = calibration.from_cache
                                 ? std::string("read from")
                                 : "calibrated (" + std::to_string(calibration.frames) + " frames) and cached in";
    char note[768];
    std::snprintf(note, sizeof note,
                  "model %s %s (%zu configurations predicted); the %zu comparable sweep points span %.1f-%.1f ms; "
                  "measured / predicted frame time over %zu of them: median %.2f, %.2f-%.2f; error model: "
                  "%u VPLs' error %.4f RMSE against %u's; svgf floor, kept noise share: %s",
                  made.c_str(), calibration.cache_file.string().c_str(), candidates.size(), comparable.size(), lo, hi,
                  ratios.size(), median(ratios), ratios.empty() ? 0.0 : *std::min_element(ratios.begin(), ratios.end()),
                  ratios.empty() ? 0.0 : *std::max_element(ratios.begin(), ratios.end()),
                  calibration.model.error.vpl_small, std::sqrt(calibration.model.error.vpl_small_mse),
                  calibration.model.error.vpl_measured, svgf_effects(calibration.model.error).c_str());
    run.budget_note = note;

    std::vector<BenchPoint> measured;  // each distinct choice once
    std::vector<BudgetConfig> measured_configs;
    // Twice: the model as calibrated (what `render --budget-ms` does), and its times scaled by the
    // median measured / predicted ratio (what a sequence's BudgetDrift re-plans to after its
    // first frames: the machine's load at the calibration is not the load now).
    const double drift = ratios.empty() ? 1.0 : median(ratios);
    for (double scale : {1.0, drift}) {
        const std::vector<BudgetCandidate> scaled = scaled_candidates(candidates, scale);
        for (double fraction : in.fractions) {
            BudgetCheckRow row;
            row.fraction = fraction;
            row.scale = scale;
            row.budget_ms = lo + fraction * (hi - lo);
            const BudgetChoice choice = choose_for_budget(scaled, row.budget_ms);
            const BudgetConfig& c = choice.chosen.config;
            row.chosen = short_config(c);
            row.predicted_ms = choice.chosen.predicted_ms;
            row.predicted_rmse = choice.chosen.predicted_rmse;
            row.over_budget = choice.over_budget;
            size_t index = 0;
            while (index < measured_configs.size() && !same_config(measured_configs[index], c)) ++index;
            if (index == measured_configs.size()) {
                BenchPoint p;
                p.method = gi_method_name(c.method);
                p.sweep = "budget";
                p.spp = c.spp;
                p.block = c.block_size;
                p.half = c.half_resolution;
                p.denoised = c.denoise == DenoiseMode::svgf;
                p.vpls = c.vpls;
                std::fprintf(stderr, "[bench] budget %.1f ms: measuring %s\n", row.budget_ms, row.chosen.c_str());
                std::string failure;
                if (!measure_bench_point(renderer, scene.camera(), apply_budget_config(base, c, source), in.frames,
                                         *in.truth_rgb, *in.truth_radiance, in.out, p, failure)) {
                    run.skipped.push_back("budget choice " + row.chosen + ": " + failure);
                    continue;
                }
                measured.push_back(p);
                measured_configs.push_back(c);
            }
            row.measured_ms = measured[index].frame_ms;
            row.measured_rmse = measured[index].rmse;
            // The best measured within B: the sweep's comparable points and the choices measured.
            const BenchPoint* best = nullptr;
            std::string best_name;
            for (const BenchPoint* p : comparable) {
                if (p->frame_ms <= row.budget_ms && (!best || p->rmse < best->rmse)) {
                    best = p;
                    best_name = p->label();
                }
            }
            for (size_t i = 0; i < measured.size(); ++i) {
                if (measured[i].frame_ms <= row.budget_ms && (!best || measured[i].rmse < best->rmse)) {
                    best = &measured[i];
                    best_name = short_config(measured_configs[i]) + " (a choice)";
                }
            }
            if (best) {
                row.best = best_name;
                row.best_ms = best->frame_ms;
                row.best_rmse = best->rmse;
            }
            run.budget_check.push_back(row);
        }
    }
}

}  // namespace vplkit::cli
