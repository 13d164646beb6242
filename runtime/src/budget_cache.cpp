// The budget model's cache file (budget_cache.hpp). Numbers are written with 17 significant
// digits so a model read back predicts exactly what the fitted one did.

#include "budget_cache.hpp"

#include "vplkit/cache_key.hpp"
#include "vplkit/error.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

namespace vplkit::detail {
namespace {

constexpr const char* kFormat = "vplkit-budget-cache 6";  // 2: slopes >= 0; 3: noise exponents; 4: no first-dispatch
                                                          // compiles in the times; 5: the VPL budget's error, svgf's
                                                          // effect per method; 6: svgf against rtslc at 64 spp

}  // namespace

std::filesystem::path budget_cache_file(const std::filesystem::path& dir, const std::string& key) {
    return dir / ("budget-" + fnv1a_hex(key) + ".txt");
}

std::optional<BudgetModel> read_budget_cache(const std::filesystem::path& file, const std::string& key) {
    std::ifstream in(file);
    if (!in) return std::nullopt;
    std::string format, key_line;
    if (!std::getline(in, format) || format != kFormat) return std::nullopt;
    if (!std::getline(in, key_line) || key_line != "key " + key) return std::nullopt;
    BudgetModel model;
    std::string line;
    bool complete = false;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string kind;
        fields >> kind;
        if (kind == "stage") {
            uint32_t tag = 0;
            size_t count = 0;
            fields >> tag >> count;
            std::vector<double> c(count);
            for (double& v : c) fields >> v;
            if (!fields) return std::nullopt;
            try {
                model.cost.set_coefficients(tag, std::move(c));
            } catch (const Error&) {
                return std::nullopt;  // another feature set: a stale format
            }
        } else if (kind == "noise") {
            NoiseMeasurement m;
            int method = 0, half = 0;
            int has_svgf = 0;
            fields >> method >> half >> m.block_size >> m.spp >> m.variance >> m.exponent >> has_svgf;
            if (has_svgf) {
                SvgfEffect svgf;
                fields >> svgf.floor_variance >> svgf.noise_share;
                m.svgf = svgf;
            }
            if (!fields) return std::nullopt;
            m.method = GiMethod(method);
            m.half_resolution = half != 0;
            model.error.sampling.push_back(m);
        } else if (kind == "vpl_budget") {
            fields >> model.error.vpl_measured >> model.error.vpl_small >> model.error.vpl_small_mse;
            if (!fields) return std::nullopt;
        } else if (kind == "end") {
            complete = true;
        } else {
            return std::nullopt;
        }
    }
    if (!complete) return std::nullopt;
    return model;
}

void write_budget_cache(const std::filesystem::path& file, const std::string& key, const BudgetModel& model) {
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec) throw Error("budget cache: cannot create " + file.parent_path().string() + ": " + ec.message());
    const std::filesystem::path temporary = file.string() + ".tmp";
    {
        std::ofstream out(temporary);
        out.precision(17);
        out << kFormat << "\nkey " << key << "\n";
        for (const auto& [tag, c] : model.cost.coefficients()) {
            out << "stage " << tag << " " << c.size();
            for (double v : c) out << " " << v;
            out << "\n";
        }
        for (const NoiseMeasurement& m : model.error.sampling) {
            out << "noise " << int(m.method) << " " << (m.half_resolution ? 1 : 0) << " " << m.block_size << " "
                << m.spp << " " << m.variance << " " << m.exponent << " " << (m.svgf ? 1 : 0);
            if (m.svgf) out << " " << m.svgf->floor_variance << " " << m.svgf->noise_share;
            out << "\n";
        }
        out << "vpl_budget " << model.error.vpl_measured << " " << model.error.vpl_small << " "
            << model.error.vpl_small_mse << "\nend\n";
        out.close();
        if (!out) {
            std::filesystem::remove(temporary, ec);
            throw Error("budget cache: cannot write " + temporary.string());
        }
    }
    std::filesystem::rename(temporary, file, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(temporary, ec);
        throw Error("budget cache: cannot write " + file.string() + ": " + why);
    }
}

}  // namespace vplkit::detail
