#include "flc_test_mesh.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

namespace flc_test {

namespace {

uint32_t next_random(const Mesh& mesh) {
    return vplkit::scene::vertex_random_value(0, 0, 0, uint32_t(mesh.positions.size()));
}

// rng.glsl's pcg_hash, which the shader applies to the seed.
uint32_t pcg_hash(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

}  // namespace

Mesh grid(uint32_t n, float cell) {
    Mesh mesh;
    for (uint32_t y = 0; y <= n; ++y) {
        for (uint32_t x = 0; x <= n; ++x) {
            mesh.random.push_back(next_random(mesh));
            mesh.positions.push_back(glm::vec3(float(x) * cell, float(y) * cell, 0.0f));
        }
    }
    for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < n; ++x) {
            const uint32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
    }
    return mesh;
}

void add_triangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    for (const glm::vec3& p : {a, b, c}) {
        mesh.indices.push_back(uint32_t(mesh.positions.size()));
        mesh.random.push_back(next_random(mesh));
        mesh.positions.push_back(p);
    }
}

Mesh transformed(const Mesh& mesh, const glm::mat4& transform) {
    Mesh out = mesh;
    for (glm::vec3& p : out.positions) p = glm::vec3(transform * glm::vec4(p, 1.0f));
    return out;
}

std::vector<vplkit::shaders::FlcCandidate> run_candidates(const Mesh& mesh,
                                                          const vplkit::stages::FlcPartition& partition,
                                                          uint32_t seed) {
    vplkit::Context& ctx = vplkit::test::context();
    std::vector<vplkit::scene::Vertex> vertices(mesh.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i) {
        vertices[i].position = mesh.positions[i];
        vertices[i].normal = glm::vec3(0.0f, 0.0f, 1.0f);
    }
    auto create = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
    };
    const uint32_t count = mesh.triangle_count();
    auto vertex_buffer = create(vertices.size() * sizeof(vplkit::scene::Vertex), "flc vertices");
    auto index_buffer = create(mesh.indices.size() * sizeof(uint32_t), "flc indices");
    auto random_buffer = create(mesh.random.size() * sizeof(uint32_t), "flc vertex random");
    auto candidates = create(count * sizeof(vplkit::shaders::FlcCandidate), "flc candidates");
    vertex_buffer.upload(vertices);
    index_buffer.upload(mesh.indices);
    random_buffer.upload(mesh.random);

    vplkit::PassList passes("flc candidates test");
    vplkit::stages::add_flc_candidates_pass(ctx, passes, {vertex_buffer, index_buffer, random_buffer, candidates},
                                            partition, count, seed);
    passes.run(ctx);
    return candidates.download<vplkit::shaders::FlcCandidate>(count);
}

double triangle_u(const Mesh& mesh, uint32_t t, uint32_t seed) {
    const uint32_t bits = pcg_hash(mesh.random[mesh.indices[3 * t]] ^ mesh.random[mesh.indices[3 * t + 1]] ^
                                   mesh.random[mesh.indices[3 * t + 2]] ^ pcg_hash(seed));
    return double(bits >> 8u) / 16777216.0;
}

}  // namespace flc_test
