// Animations: every channel's keys read and checked before anything is posed, so a malformed
// animation is one error naming the file, the animation and the channel, and the posed model is
// never half written.

#include "scene/gltf_animation.hpp"

#include "scene/gltf_animation_sampler.hpp"
#include "scene/gltf_checks.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace vplkit::scene::detail {
namespace {

struct ReadChannel {
    int node = -1;
    KeyedChannel keys;
    std::string label;  // "animation 0 'swing' channel 1 (node 2 'lamp' rotation)"
};

struct ReadAnimation {
    Animation info;
    std::string label;           // "animation 0 'swing'"
    std::string index_and_name;  // "0 'swing'"
    std::vector<ReadChannel> channels;
};

std::string seconds(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g s", t);
    return text;
}

const char* path_name(AnimatedPath path) {
    switch (path) {
        case AnimatedPath::translation:
            return "translation";
        case AnimatedPath::rotation:
            return "rotation";
        case AnimatedPath::scale:
            return "scale";
        case AnimatedPath::weights:
            return "weights";
    }
    return "";
}

// The morph target count of the mesh on `node`: how many values a weights channel gives per key.
size_t morph_target_count(const GltfSource& source, const tinygltf::Node& node, const std::string& label) {
    if (node.mesh < 0) source.fail(label + " animates morph weights, but the node has no mesh");
    check_index(source, node.mesh, source.model.meshes, "mesh", label);
    const tinygltf::Mesh& mesh = source.model.meshes[size_t(node.mesh)];
    const size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    if (targets == 0) source.fail(label + " animates morph weights, but the node's mesh has no morph targets");
    return targets;
}

// Channel `c` of `animation`, its sampler's keys checked: times finite and strictly increasing,
// values finite, as many values as keys (times 3 for CUBICSPLINE, times the morph target count
// for weights). Returns nothing for a path glTF 2.0 does not define (an extension's): warned.
std::optional<ReadChannel> read_channel(const GltfSource& source, const tinygltf::Animation& animation,
                                        const std::string& animation_label, size_t c, LoadWarnings& warnings) {
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    ReadChannel out;
    out.label = animation_label + " channel " + std::to_string(c);
    check_index(source, channel.target_node, source.model.nodes, "node", out.label);
    out.node = channel.target_node;
    const tinygltf::Node& node = source.model.nodes[size_t(out.node)];
    KeyedChannel& keys = out.keys;
    const std::string& path = channel.target_path;
    if (path == "translation") {
        keys.path = AnimatedPath::translation;
    } else if (path == "rotation") {
        keys.path = AnimatedPath::rotation;
    } else if (path == "scale") {
        keys.path = AnimatedPath::scale;
    } else if (path == "weights") {
        keys.path = AnimatedPath::weights;
    } else {
        warnings.messages.push_back(out.label + " animates path '" + path +
                                    "', which is not a glTF 2.0 node property: skipped");
        return std::nullopt;
    }
    out.label += " (node " + std::to_string(out.node) + quoted_name(node.name) + " " + path + ")";
    if (!node.matrix.empty()) {
        source.fail(out.label + ": the node has a matrix, and glTF 2.0 animates only nodes with TRS properties");
    }
    check_index(source, channel.sampler, animation.samplers, "sampler", out.label);
    const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
    const std::string sampler_label = out.label + " sampler " + std::to_string(channel.sampler);
    if (sampler.interpolation == "LINEAR") {
        keys.interpolation = Interpolation::linear;
    } else if (sampler.interpolation == "STEP") {
        keys.interpolation = Interpolation::step;
    } else if (sampler.interpolation == "CUBICSPLINE") {
        keys.interpolation = Interpolation::cubic_spline;
    } else {
        source.fail(sampler_label + ": interpolation '" + sampler.interpolation +
                    "' is not LINEAR, STEP or CUBICSPLINE");
    }

    const std::vector<float> times = read_floats(source, sampler.input, 1, kAdmitFloat, 0, sampler_label + " input");
    for (size_t k = 0; k < times.size(); ++k) {
        if (!finite(times[k])) source.fail(sampler_label + ": input time " + std::to_string(k) + " is not finite");
        if (k > 0 && !(times[k] > times[k - 1])) {
            source.fail(sampler_label + ": input times are not strictly increasing (key " + std::to_string(k) + " at " +
                        seconds(times[k]) + " follows " + seconds(times[k - 1]) + ")");
        }
    }
    keys.times.assign(times.begin(), times.end());

    // Rotations and weights may be normalized integers (glTF 2.0 3.11); translations and scales are floats.
    const bool rotation_or_weights = keys.path == AnimatedPath::rotation || keys.path == AnimatedPath::weights;
    const uint32_t admits =
        kAdmitFloat | (rotation_or_weights ? kAdmitNormalizedUnsigned | kAdmitNormalizedSigned : 0u);
    const size_t element = keys.path == AnimatedPath::weights ? 1 : keys.path == AnimatedPath::rotation ? 4 : 3;
    keys.components = keys.path == AnimatedPath::weights ? morph_target_count(source, node, out.label) : element;
    const std::vector<float> values =
        read_floats(source, sampler.output, element, admits, 0, sampler_label + " output");
    const size_t per_key = (keys.interpolation == Interpolation::cubic_spline ? 3 : 1) * keys.components;
    if (values.size() != times.size() * per_key) {
        const size_t elements = values.size() / element, expected = times.size() * per_key / element;
        std::string why =
            std::to_string(times.size()) + " input key(s) need " + std::to_string(expected) + " output element(s)";
        if (keys.interpolation == Interpolation::cubic_spline) why += " (in-tangent, value, out-tangent per key)";
        if (keys.path == AnimatedPath::weights) why += " (" + std::to_string(keys.components) + " morph targets)";
        source.fail(sampler_label + ": " + why + ", but the output has " + std::to_string(elements));
    }
    for (float v : values) {
        if (!finite(v)) source.fail(sampler_label + ": an output value is not finite");
    }
    keys.values.assign(values.begin(), values.end());
    return out;
}

ReadAnimation read_animation(const GltfSource& source, size_t index, LoadWarnings& warnings) {
    const tinygltf::Animation& animation = source.model.animations[index];
    ReadAnimation out;
    out.info.name = animation.name;
    out.index_and_name = std::to_string(index) + quoted_name(animation.name);
    out.label = "animation " + out.index_and_name;
    std::map<std::pair<int, AnimatedPath>, size_t> animated;  // glTF 2.0: each target once per animation
    bool first = true;
    for (size_t c = 0; c < animation.channels.size(); ++c) {
        std::optional<ReadChannel> channel = read_channel(source, animation, out.label, c, warnings);
        if (!channel) continue;
        const auto [it, fresh] = animated.emplace(std::make_pair(channel->node, channel->keys.path), c);
        if (!fresh) {
            source.fail(channel->label + " animates what channel " + std::to_string(it->second) +
                        " does (glTF 2.0 allows each node property once per animation)");
        }
        const double start = channel->keys.times.front(), end = channel->keys.times.back();
        out.info.start = first ? start : std::min(out.info.start, start);
        out.info.end = first ? end : std::max(out.info.end, end);
        first = false;
        out.channels.push_back(std::move(*channel));
    }
    return out;
}

// The animation `selector` names: by name first, else by decimal index.
size_t select_animation(const GltfSource& source, const std::vector<ReadAnimation>& animations,
                        const std::string& selector) {
    for (size_t a = 0; a < animations.size(); ++a) {
        if (!selector.empty() && animations[a].info.name == selector) return a;
    }
    const bool digits = !selector.empty() && selector.size() < 10 &&
                        std::all_of(selector.begin(), selector.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    if (digits && std::stoul(selector) < animations.size()) return std::stoul(selector);
    std::string have = "no animation";
    if (!animations.empty()) {
        have = std::to_string(animations.size()) + " animation(s):";
        for (size_t a = 0; a < animations.size(); ++a) have += (a ? ", " : " ") + animations[a].index_and_name;
    }
    source.fail("animation '" + selector + "' was asked for, but the file has " + have);
}

// Writes the channel's value at t into its node's property.
void pose_node(tinygltf::Model& model, const ReadChannel& channel, double t) {
    std::vector<double> value = sample_channel(channel.keys, t);
    tinygltf::Node& node = model.nodes[size_t(channel.node)];
    switch (channel.keys.path) {
        case AnimatedPath::translation:
            node.translation = std::move(value);
            break;
        case AnimatedPath::rotation:
            node.rotation = std::move(value);  // (x, y, z, w), as the file stores it
            break;
        case AnimatedPath::scale:
            node.scale = std::move(value);
            break;
        case AnimatedPath::weights:
            node.weights = std::move(value);  // a node's weights take precedence over its mesh's
            break;
    }
}

}  // namespace

std::vector<Animation> pose_animations(const GltfSource& source, tinygltf::Model& model, const LoadOptions& options,
                                       std::optional<double>& time, LoadWarnings& warnings) {
    std::vector<ReadAnimation> animations;
    for (size_t a = 0; a < model.animations.size(); ++a) animations.push_back(read_animation(source, a, warnings));
    std::optional<size_t> selected;
    if (options.animation) selected = select_animation(source, animations, *options.animation);

    time.reset();
    if (options.time || selected) {
        const double t = options.time ? *options.time : animations[*selected].info.start;
        if (!finite(t)) source.fail("the time to pose the scene at is not finite");
        time = t;
        if (animations.empty()) {
            warnings.messages.push_back(
                "a time was given, but the file has no animation: the still frame is its "
                "rest pose");
        }
        // Later animations win where two animate the same node property (warned once per pair).
        std::map<std::pair<int, AnimatedPath>, size_t> posed_by;
        std::set<std::pair<size_t, size_t>> warned;
        for (size_t a = 0; a < animations.size(); ++a) {
            if (selected && a != *selected) continue;
            animations[a].info.applied = true;
            for (const ReadChannel& channel : animations[a].channels) {
                const auto key = std::make_pair(channel.node, channel.keys.path);
                if (auto it = posed_by.find(key);
                    it != posed_by.end() && it->second != a && warned.emplace(it->second, a).second) {
                    warnings.messages.push_back(animations[it->second].label + " and " + animations[a].label +
                                                " both animate node " + std::to_string(channel.node) + " " +
                                                path_name(channel.keys.path) +
                                                ": the later one's values are used where they overlap (select "
                                                "one animation to play only it)");
                }
                posed_by[key] = a;
                pose_node(model, channel, t);
            }
        }
    } else if (!animations.empty()) {
        warnings.messages.push_back(
            std::to_string(animations.size()) +
            " animation(s) ignored: no time was given, so the still frame is the file's "
            "rest pose (node transforms, default morph weights); set a time to pose the scene at it");
    }
    std::vector<Animation> out;
    for (const ReadAnimation& animation : animations) out.push_back(animation.info);
    return out;
}

}  // namespace vplkit::scene::detail
