#include "vplkit/antialias.hpp"

#include "vplkit/error.hpp"

namespace vplkit {

namespace {

// The radical inverse of `index` in `base`: its digits mirrored about the point.
float radical_inverse(uint32_t index, uint32_t base) {
    double result = 0.0, digit = 1.0 / base;
    for (; index > 0; index /= base, digit /= base) result += double(index % base) * digit;
    return float(result);
}

}  // namespace

glm::vec2 subpixel_jitter(uint32_t frame) {
    if (frame == 0) return glm::vec2(0.0f);
    const uint32_t index = (frame - 1) % 1024 + 1;
    return glm::vec2(radical_inverse(index, 2), radical_inverse(index, 3)) - 0.5f;
}

stages::CameraView jittered_view(const stages::CameraView& view, glm::vec2 offset, uint32_t width, uint32_t height) {
    if (width == 0 || height == 0) throw Error("jittered_view: zero image size");
    // A pixel is 2 / width of clip space (x / w); the shift is scaled by w so that it holds at
    // every depth, perspective or orthographic (w = 1).
    glm::mat4 shift(1.0f);
    shift[3][0] = 2.0f * offset.x / float(width);
    shift[3][1] = 2.0f * offset.y / float(height);
    stages::CameraView out = view;
    out.view_projection = shift * view.view_projection;
    return out;
}

std::vector<float> FrameAccumulator::add(uint32_t frame, const glm::mat4& view_projection, bool average_indirect,
                                         std::vector<float>& direct, std::vector<float>& indirect,
                                         std::vector<float>& radiance) {
    if (direct.size() != indirect.size() || direct.size() != radiance.size()) {
        throw Error("frame accumulator: the direct, indirect and radiance images differ in size");
    }
    if (frame == 0 || direct.size() != direct_.size() || view_projection != view_projection_) count_ = 0;
    view_projection_ = view_projection;
    ++count_;
    if (count_ == 1) {
        direct_ = direct;
        indirect_ = indirect;
    } else {
        // A running mean: the n-th frame weighs 1/n.
        const float weight = 1.0f / float(count_);
        for (size_t i = 0; i < direct.size(); ++i) {
            direct_[i] += (direct[i] - direct_[i]) * weight;
            indirect_[i] += (indirect[i] - indirect_[i]) * weight;
        }
    }
    direct = direct_;
    if (average_indirect) indirect = indirect_;
    std::vector<float> rgba;
    rgba.reserve(radiance.size() / 3 * 4);
    for (size_t i = 0; i < radiance.size(); ++i) {
        radiance[i] = direct[i] + indirect[i];
        rgba.push_back(radiance[i]);
        if (i % 3 == 2) rgba.push_back(1.0f);
    }
    return rgba;
}

}  // namespace vplkit
