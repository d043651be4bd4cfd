// Without a GPU: a post-processing chain expands into passes whose targets are exactly what its
// effects write, and the blur's kernel.
#include <catch2/catch.hpp>

#include <numeric>
#include <set>

#include <dstrans/post.hpp>

using namespace dstrans;

TEST_CASE("a chain expands into its effects' passes, and allocates only what they write", "[post]") {
  CHECK(plan_post({}, true).passes.empty());
  CHECK(plan_post({}, true).targets.empty());
  CHECK(plan_post({}, true).output == "frame");
  post_effect aa{post_kind::antialias}, bloom{post_kind::bloom}, blur{post_kind::blur}, grey{post_kind::greyscale};
  const post_plan p = plan_post({aa, bloom, blur, blur, grey}, true);
  CHECK(p.effects == std::vector<std::string>{"aa", "bloom", "blur", "blur_2", "greyscale"});
  CHECK(p.output == "greyscale");
  std::vector<std::string> names;
  for (const post_pass& pass : p.passes) names.push_back(pass.name);
  CHECK(names == std::vector<std::string>{"aa", "bloom.bright", "bloom.blur.horizontal", "bloom.blur", "bloom", "blur.horizontal",
                                          "blur", "blur_2.horizontal", "blur_2", "greyscale"});
  CHECK(std::set<std::string>(p.targets.begin(), p.targets.end()).size() == p.targets.size());
  CHECK(p.targets == names);  // one target per pass, each written once
  // Each effect reads the one before; the first reads the frame; bloom adds its blur to its own input.
  CHECK(p.passes[0].inputs == std::vector<std::string>{"frame", "gbuffer"});
  CHECK(p.passes[1].inputs == std::vector<std::string>{"aa"});
  CHECK(p.passes[4].inputs == std::vector<std::string>{"aa", "bloom.blur"});
  CHECK(p.passes[5].inputs == std::vector<std::string>{"bloom"});
  CHECK(p.passes[9].inputs == std::vector<std::string>{"blur_2"});
  // Anti-aliasing compares the surfaces in front only on an interlaced frame, and only if asked.
  CHECK(p.passes[0].switches == std::vector<std::string>{"DST_AA_INTERLACE"});
  CHECK(plan_post({aa}, false).passes[0].switches.empty());
  aa.interlace = false;
  CHECK(plan_post({aa}, true).passes[0].switches.empty());
  post_effect sepia{post_kind::sepia};
  CHECK(plan_post({sepia}, true).passes[0].switches == std::vector<std::string>{"DST_SEPIA"});
  post_effect dof{post_kind::depth_of_field};
  dof.focus = 3.0f;
  const post_plan d = plan_post({dof}, true);
  REQUIRE(d.passes.size() == 3);
  CHECK(d.passes[2].inputs == std::vector<std::string>{"frame", "dof.blur", "gbuffer"});
  CHECK(d.passes[2].params[0] == 3.0f);
}

TEST_CASE("the blur's kernel is a normalised, symmetric Gaussian", "[post]") {
  for (float sigma : {0.5f, 2.0f, 8.0f}) {
    const std::vector<float> w = gaussian_weights(4, sigma);
    REQUIRE(w.size() == 9);
    CHECK(std::accumulate(w.begin(), w.end(), 0.0f) == Approx(1.0f).epsilon(1e-6));
    for (int i = 0; i < 4; ++i) CHECK(w[std::size_t(i)] == w[std::size_t(8 - i)]);
    for (int i = 0; i < 4; ++i) CHECK(w[std::size_t(i)] < w[std::size_t(i + 1)]);
  }
  CHECK(gaussian_weights(3, 0.0f) == std::vector<float>{0, 0, 0, 1, 0, 0, 0});  // sigma 0: no blur
  CHECK(gaussian_weights(0, 2.0f) == std::vector<float>{1});
}

TEST_CASE("the tone and bloom formulas keep black black and what is below the threshold out", "[post]") {
  CHECK(shader::dst_luminance(glm::vec3(1.0f)) == Approx(0.99f));
  CHECK(shader::dst_greyscale(glm::vec3(0.0f)) == glm::vec3(0.0f));
  CHECK(shader::dst_sepia(glm::vec3(0.0f)) == glm::vec3(0.0f));
  CHECK(shader::dst_bright_pass(glm::vec3(0.4f), 0.5f) == glm::vec3(0.0f));
  const glm::vec3 kept = shader::dst_bright_pass(glm::vec3(1.0f), 0.495f);
  CHECK(kept.x == Approx(0.5f));
  CHECK(shader::dst_blur_amount(7.0f, 5.0f, 2.0f) == 1.0f);
  CHECK(shader::dst_blur_amount(6.0f, 5.0f, 2.0f) == 0.5f);
  // The edge weight: none on a plane, none for a smooth turn, full across a fold or a depth jump.
  const glm::vec3 z(0, 0, 1), tilted = glm::normalize(glm::vec3(0.2f, 0, 1)), side(1, 0, 0);
  CHECK(shader::dst_edge_weight(z, z, 5.0f, 5.01f, 4.0f, 20.0f) == 0.0f);
  CHECK(shader::dst_edge_weight(z, tilted, 5.0f, 5.0f, 4.0f, 20.0f) == 0.0f);
  CHECK(shader::dst_edge_weight(z, side, 5.0f, 5.0f, 4.0f, 20.0f) == 1.0f);
  CHECK(shader::dst_edge_weight(z, z, 5.0f, 8.0f, 4.0f, 20.0f) == 1.0f);
}
