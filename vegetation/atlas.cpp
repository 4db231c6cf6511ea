#include "vegetation/atlas.h"

#include "common/error.h"
#include "common/hash.h"
#include "io/image_io.h"
#include "common/noise.h"
#include "vegetation/vegetation_params.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace sward {

using glm::vec2;
using glm::vec3;
using glm::vec4;

// ---------------------------------------------------------------------------------------------------------------
// Layout

uint32_t AtlasDesc::maxColumns() const {
    size_t columns = 0;
    for (const AtlasRow& row : rows) columns = std::max(columns, row.cells.size());
    return uint32_t(columns);
}

uint32_t AtlasDesc::mipLevelCount() const {
    return uint32_t(std::bit_width(std::min(cellWidth, cellHeight)));
}

AtlasRect AtlasDesc::cellRect(uint32_t row, uint32_t column, uint32_t level) const {
    assert(row < rows.size() && column < maxColumns() && level < mipLevelCount());
    const uint32_t w = cellWidth >> level, h = cellHeight >> level;
    return {column * w, row * h, w, h};
}

std::array<float, 4> AtlasDesc::cellUvRect(uint32_t row, uint32_t column) const {
    const float cu = 1.0f / float(maxColumns()), cv = 1.0f / float(rows.size());
    return {float(column) * cu, float(row) * cv, float(column + 1) * cu, float(row + 1) * cv};
}

// ---------------------------------------------------------------------------------------------------------------
// Colour

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Decoding table and the linear midpoints between consecutive codes: encoding by search in this table makes
// encode(decode(b)) == b for every byte, so mipmapping a flat colour never drifts.
struct SrgbTable {
    std::array<float, 256> toLinear{};
    std::array<float, 255> midpoints{};
};

const SrgbTable& srgbTable() {
    static const SrgbTable table = [] {
        SrgbTable t;
        for (int i = 0; i < 256; ++i) t.toLinear[i] = srgbToLinear(float(i) / 255.0f);
        for (int i = 0; i < 255; ++i) t.midpoints[i] = 0.5f * (t.toLinear[i] + t.toLinear[i + 1]);
        return t;
    }();
    return table;
}

uint8_t encodeSrgb(float linear) {
    const auto& m = srgbTable().midpoints;
    return uint8_t(std::upper_bound(m.begin(), m.end(), linear) - m.begin());
}

uint8_t encodeUnorm(float v) {
    return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

// Palette entries are written in sRGB (as a painter picks them) and painted in linear light.
vec3 srgb(float r, float g, float b) {
    return {srgbToLinear(r), srgbToLinear(g), srgbToLinear(b)};
}

// ---------------------------------------------------------------------------------------------------------------
// Painting: every plant part is a stroke, a polyline with a half-width per point, rasterised with analytic
// one-texel edge coverage (the soft alpha at blade edges that alpha-to-coverage turns into smooth silhouettes).

struct Stroke {
    std::vector<vec2> points; // centreline in cell texels (y down), from the attached end
    std::vector<float> halfWidths;
    vec3 base{0.0f}, tip{0.0f}; // linear colour at the attached end and at the free end
    float tipStart = 1.0f;      // fraction of the length where the colour starts turning to `tip`
    float shadeBase = 0.0f;     // darkening at the attached end: self-shadowing deep inside a clump
    float sideShade = 0.15f;    // one half darker than the other: reads as a folded blade or leaf
    float midrib = 0.0f;        // lighter centre line
};

float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

vec2 direction(float angleFromUp) {
    return {std::sin(angleFromUp), -std::cos(angleFromUp)};
}

std::vector<vec2> cubicBezier(vec2 p0, vec2 p1, vec2 p2, vec2 p3, int count) {
    std::vector<vec2> points(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        const float t = float(i) / float(count - 1), u = 1.0f - t;
        points[size_t(i)] = u * u * u * p0 + 3.0f * u * u * t * p1 + 3.0f * u * t * t * p2 + t * t * t * p3;
    }
    return points;
}

// Point and unit tangent at fraction t of a polyline's vertex sequence (vertices roughly evenly spaced).
std::pair<vec2, vec2> alongPolyline(const std::vector<vec2>& points, float t) {
    const float f = std::clamp(t, 0.0f, 1.0f) * float(points.size() - 1);
    const size_t i = std::min(size_t(f), points.size() - 2);
    const vec2 a = points[i], b = points[i + 1];
    return {a + (b - a) * (f - float(i)), glm::normalize(b - a)};
}

vec2 rotate(vec2 v, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// One cell being painted: premultiplied linear RGBA, composited "over" stroke by stroke.
class CellCanvas {
public:
    CellCanvas(uint32_t size, uint64_t grainSeed) : size_(size), grainSeed_(grainSeed), texels_(size_t(size) * size) {}

    uint32_t size() const { return size_; }
    const vec4& texel(uint32_t x, uint32_t y) const { return texels_[size_t(y) * size_ + x]; }

    void draw(const Stroke& stroke) {
        const size_t n = stroke.points.size();
        assert(n >= 2 && stroke.halfWidths.size() == n);
        vec2 lo(1e30f), hi(-1e30f);
        for (size_t i = 0; i < n; ++i) {
            lo = glm::min(lo, stroke.points[i] - stroke.halfWidths[i] - 1.0f);
            hi = glm::max(hi, stroke.points[i] + stroke.halfWidths[i] + 1.0f);
        }
        const int x0 = std::max(0, int(std::floor(lo.x))), y0 = std::max(0, int(std::floor(lo.y)));
        const int x1 = std::min(int(size_) - 1, int(hi.x)), y1 = std::min(int(size_) - 1, int(hi.y));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) shade(stroke, x, y);
    }

private:
    void shade(const Stroke& s, int x, int y) {
        const vec2 p(float(x) + 0.5f, float(y) + 0.5f);
        float coverage = 0.0f, t = 0.0f, lateral = 0.0f;
        const size_t segments = s.points.size() - 1;
        for (size_t i = 0; i < segments; ++i) {
            const vec2 a = s.points[i], ab = s.points[i + 1] - a, ap = p - a;
            const float len2 = glm::dot(ab, ab);
            const float h = len2 > 0.0f ? std::clamp(glm::dot(ap, ab) / len2, 0.0f, 1.0f) : 0.0f;
            const float dist = glm::length(ap - ab * h);
            const float hw = s.halfWidths[i] + (s.halfWidths[i + 1] - s.halfWidths[i]) * h;
            // Box-filtered edge: full coverage one half texel inside the edge, none one half texel outside; a
            // stroke thinner than a texel is capped at its width so hairlines fade instead of staying solid.
            const float c = std::clamp(hw + 0.5f - dist, 0.0f, std::min(2.0f * hw, 1.0f));
            if (c > coverage) {
                coverage = c;
                t = (float(i) + h) / float(segments);
                const float side = ab.x * ap.y - ab.y * ap.x >= 0.0f ? 1.0f : -1.0f;
                lateral = hw > 0.0f ? side * std::min(dist / hw, 1.0f) : 0.0f;
            }
        }
        if (coverage <= 0.0f) return;

        vec3 colour = glm::mix(s.base, s.tip, smoothstep(s.tipStart, 1.0f, t));
        colour *= 1.0f - s.shadeBase * (1.0f - smoothstep(0.0f, 0.45f, t));
        colour *= 1.0f + s.sideShade * lateral;
        colour *= 1.0f + s.midrib * std::max(0.0f, 1.0f - std::abs(lateral) * 3.0f);
        const float grain = float(valueNoise(grainSeed_, 0, double(p.x) / 3.0, double(p.y) / 3.0));
        colour = glm::clamp(colour * (1.0f + 0.07f * grain), 0.0f, 1.0f);

        vec4& dst = texels_[size_t(y) * size_ + size_t(x)];
        dst = vec4(colour * coverage, coverage) + dst * (1.0f - coverage);
    }

    uint32_t size_;
    uint64_t grainSeed_;
    std::vector<vec4> texels_;
};

// Random numbers for one cell, drawn from a HashStream so a cell is a pure function of (seed, row kind, column).
struct Dice {
    HashStream stream;
    float operator()() { return stream.nextFloat(); }
    float range(float lo, float hi) { return lo + (hi - lo) * stream.nextFloat(); }
    float centred() { return stream.nextFloat() + stream.nextFloat() - 1.0f; } // triangular in (-1, 1)
    vec3 jitter(vec3 c, float amount) {
        const float k = range(1.0f - amount, 1.0f + amount);
        return glm::clamp(c * k * vec3(range(0.95f, 1.05f), range(0.95f, 1.05f), range(0.95f, 1.05f)), 0.0f, 1.0f);
    }
};

// Half-width profiles over t in [0, 1].
float bladeProfile(float t) {
    return (1.0f - 0.3f * t) * std::pow(std::min(1.0f, (1.0f - t) * 2.2f), 0.9f);
}
float leafProfile(float t) {
    return std::pow(std::sin(kPi * std::clamp(t, 0.0f, 1.0f)), 0.7f);
}

template <class Profile> std::vector<float> widths(size_t count, float halfWidth, Profile profile) {
    std::vector<float> w(count);
    for (size_t i = 0; i < count; ++i) w[i] = halfWidth * profile(float(i) / float(count - 1));
    return w;
}

// A leaf from `from` along `dir` (unit), drooping by `droop` times its length at the tip.
Stroke leaf(vec2 from, vec2 dir, float length, float halfWidth, float droop, vec3 base, vec3 tip) {
    Stroke s{.base = base, .tip = tip, .tipStart = 0.3f, .sideShade = 0.2f, .midrib = 0.12f};
    for (int i = 0; i < 8; ++i) {
        const float t = float(i) / 7.0f;
        s.points.push_back(from + dir * (length * t) + vec2(0.0f, droop * length * t * t));
    }
    s.halfWidths = widths(8, halfWidth, leafProfile);
    return s;
}

// A round dot (flower floret, berry, flower disc): a very short stroke.
Stroke dot(vec2 centre, float radius, vec3 colour, float squash = 1.0f) {
    const float dx = radius * (1.0f - squash);
    return {.points = {centre - vec2(dx, 0.0f), centre + vec2(dx, 0.0f)},
            .halfWidths = {radius * squash, radius * squash},
            .base = colour,
            .tip = colour,
            .sideShade = 0.25f};
}

using Plant = std::vector<Stroke>;

// Scales a plant about its base point so that it stays `margin` texels inside the cell's top and sides: a cell
// never spills into its neighbours, and the empty border keeps bilinear filtering of small mips inside the cell.
void fitInCell(Plant& plant, float size, float margin) {
    const vec2 anchor(size * 0.5f, size);
    float scale = 1.0f;
    for (const Stroke& s : plant)
        for (size_t i = 0; i < s.points.size(); ++i) {
            const vec2 d = s.points[i] - anchor;
            const float hw = s.halfWidths[i];
            const float reachX = std::abs(d.x) + hw, reachY = -d.y + hw;
            if (reachX > 0.0f) scale = std::min(scale, (size * 0.5f - margin) / reachX);
            if (reachY > 0.0f) scale = std::min(scale, (size - margin) / reachY);
        }
    if (scale >= 1.0f) return;
    for (Stroke& s : plant) {
        for (vec2& p : s.points) p = anchor + (p - anchor) * scale;
        for (float& w : s.halfWidths) w *= scale;
    }
}

// ---- grass -----------------------------------------------------------------------------------------------------

Plant paintGrass(Dice& dice, float S, uint32_t variant) {
    Plant plant;
    const vec2 root(S * 0.5f, S);
    const int blades = 42 + int(dice() * 24.0f);
    const float spread = S * dice.range(0.08f, 0.17f);
    const float heightScale = dice.range(0.75f, 1.0f);
    // Variants alternate lush and drier clumps; every third has flowering stems with seed heads.
    const float dryFraction = (variant % 2 == 0 ? 0.15f : 0.45f) + dice.range(0.0f, 0.2f);
    const bool seedHeads = variant % 3 == 2;
    const vec3 greens[] = {srgb(0.24f, 0.42f, 0.10f), srgb(0.32f, 0.50f, 0.13f), srgb(0.20f, 0.37f, 0.09f),
                           srgb(0.40f, 0.55f, 0.17f)};
    const vec3 straw = srgb(0.80f, 0.72f, 0.45f), paleGreen = srgb(0.55f, 0.64f, 0.26f);

    for (int b = 0; b < blades; ++b) {
        const float off = dice.centred();
        const vec2 base = root + vec2(off * spread, 0.0f);
        const float lean = off * 0.5f + dice.range(-0.3f, 0.3f);
        const float length = S * heightScale * dice.range(0.45f, 0.95f) * (1.0f - 0.25f * std::abs(off));
        const float bend = (lean >= 0.0f ? 1.0f : -1.0f) * (0.1f + 0.9f * dice() * dice());
        const vec2 p1 = base + direction(lean) * length * 0.35f;
        const vec2 p2 = p1 + direction(lean + bend * 0.5f) * length * 0.35f;
        const vec2 p3 = p2 + direction(lean + bend) * length * 0.32f;
        const bool dry = dice() < dryFraction;
        Stroke s{.points = cubicBezier(base, p1, p2, p3, 16),
                 .base = dice.jitter(greens[size_t(dice() * 4.0f) & 3], 0.15f),
                 .tip = dry ? dice.jitter(straw, 0.1f) : dice.jitter(paleGreen, 0.1f),
                 .tipStart = dry ? dice.range(0.25f, 0.6f) : dice.range(0.6f, 0.85f),
                 .shadeBase = 0.55f,
                 .sideShade = 0.18f,
                 .midrib = 0.1f};
        s.halfWidths = widths(16, S * dice.range(0.005f, 0.010f), bladeProfile);
        plant.push_back(std::move(s));
    }

    if (seedHeads) {
        const int stems = 2 + int(dice() * 3.0f);
        for (int k = 0; k < stems; ++k) {
            const vec2 base = root + vec2(dice.centred() * spread * 0.6f, 0.0f);
            const float lean = dice.range(-0.3f, 0.3f), length = S * heightScale * dice.range(0.8f, 0.98f);
            const vec2 p3 = base + direction(lean + dice.range(-0.15f, 0.15f)) * length;
            const auto points = cubicBezier(base, base + direction(lean) * length * 0.4f,
                                            base + direction(lean) * length * 0.75f, p3, 14);
            plant.push_back({.points = points,
                             .halfWidths = widths(14, S * 0.0035f, [](float t) { return 1.0f - 0.5f * t; }),
                             .base = srgb(0.35f, 0.48f, 0.16f),
                             .tip = srgb(0.62f, 0.62f, 0.36f),
                             .tipStart = 0.4f,
                             .shadeBase = 0.4f});
            // Spikelets alternate along the top third, pointing upwards, smaller towards the tip.
            const vec3 husk = variant % 2 == 0 ? srgb(0.72f, 0.64f, 0.40f) : srgb(0.58f, 0.44f, 0.40f);
            const int spikelets = 9 + int(dice() * 6.0f);
            for (int i = 0; i < spikelets; ++i) {
                const float t = 0.68f + 0.32f * float(i) / float(spikelets - 1);
                const auto [at, tangent] = alongPolyline(points, t);
                const float side = i % 2 == 0 ? 1.0f : -1.0f, size = S * 0.035f * (1.1f - 0.5f * (t - 0.68f) / 0.32f);
                plant.push_back(leaf(at, rotate(tangent, side * dice.range(0.3f, 0.6f)), size, size * 0.28f, 0.0f,
                                     dice.jitter(husk, 0.12f), dice.jitter(husk * 1.15f, 0.1f)));
            }
        }
    }
    return plant;
}

// ---- ferns and forest floor ------------------------------------------------------------------------------------

void paintLitter(Plant& plant, Dice& dice, float S, int count) {
    const vec3 browns[] = {srgb(0.45f, 0.30f, 0.15f), srgb(0.56f, 0.40f, 0.20f), srgb(0.36f, 0.25f, 0.12f),
                           srgb(0.50f, 0.36f, 0.24f)};
    for (int i = 0; i < count; ++i) {
        const vec2 at(S * 0.5f + dice.centred() * S * 0.38f, S * (1.0f - dice.range(0.01f, 0.09f)));
        const float length = S * dice.range(0.04f, 0.08f);
        const vec2 dir = direction(kPi * 0.5f + dice.range(-0.5f, 0.5f)) * (dice() < 0.5f ? 1.0f : -1.0f);
        const vec3 c = dice.jitter(browns[size_t(dice() * 4.0f) & 3], 0.15f);
        plant.push_back(leaf(at - dir * (length * 0.5f), dir, length, length * 0.22f, 0.0f, c, c * 1.1f));
    }
}

Plant paintFerns(Dice& dice, float S, uint32_t variant) {
    Plant plant;
    const vec2 root(S * 0.5f, S);
    // Every fourth variant is forest floor in autumn: smaller fronds, some of them dead bracken, more litter.
    const bool autumn = variant % 4 == 3;
    paintLitter(plant, dice, S, autumn ? 22 : 12);

    const int fronds = 5 + int(dice() * 3.0f);
    const vec3 dark = srgb(0.11f, 0.27f, 0.07f), young = srgb(0.30f, 0.50f, 0.13f);
    const vec3 deadBase = srgb(0.50f, 0.32f, 0.14f), deadTip = srgb(0.68f, 0.48f, 0.22f);
    const float heightScale = autumn ? 0.75f : dice.range(0.85f, 1.0f);
    for (int f = 0; f < fronds; ++f) {
        const float a = -0.65f + 1.3f * (float(f) + 0.5f + dice.range(-0.3f, 0.3f)) / float(fronds);
        const float length = S * heightScale * dice.range(0.7f, 0.95f) * (1.0f - 0.25f * std::abs(a));
        const float droop = (a >= 0.0f ? 1.0f : -1.0f) * dice.range(0.3f, 0.7f);
        const vec2 base = root + vec2(dice.centred() * S * 0.03f, 0.0f);
        const vec2 p1 = base + direction(a * 0.7f) * length * 0.4f;
        const vec2 p2 = p1 + direction(a + droop * 0.4f) * length * 0.35f;
        const vec2 p3 = p2 + direction(a + droop) * length * 0.3f;
        const auto rachis = cubicBezier(base, p1, p2, p3, 24);
        const bool dead = autumn && dice() < 0.4f;
        const vec3 base0 = dead ? dice.jitter(deadBase, 0.1f) : dice.jitter(dark, 0.15f);
        const vec3 tip0 = dead ? dice.jitter(deadTip, 0.1f) : dice.jitter(young, 0.12f);

        // Pinnae in pairs, longest a third of the way up, shorter towards the tip; each droops a little and has
        // lobed edges (the half-width ripples) so it reads as a leaflet with pinnules.
        const int pairs = 16 + int(dice() * 6.0f);
        for (int j = 0; j < pairs; ++j) {
            const float t = 0.14f + 0.84f * float(j) / float(pairs - 1);
            const auto [at, tangent] = alongPolyline(rachis, t);
            const float profile = t < 0.3f ? 0.65f + 0.35f * t / 0.3f : 1.0f - 0.85f * (t - 0.3f) / 0.7f;
            const float plen = length * 0.23f * profile;
            for (float side : {-1.0f, 1.0f}) {
                const vec2 dir = rotate(tangent, side * dice.range(0.95f, 1.2f));
                Stroke s{.base = glm::mix(base0, tip0, t * 0.6f),
                         .tip = glm::mix(base0, tip0, 0.3f + t * 0.7f),
                         .tipStart = 0.2f,
                         .shadeBase = 0.25f,
                         .sideShade = 0.22f,
                         .midrib = 0.15f};
                for (int i = 0; i < 10; ++i) {
                    const float u = float(i) / 9.0f;
                    s.points.push_back(at + dir * (plen * u) + vec2(0.0f, 0.25f * plen * u * u));
                    const float lobes = 0.72f + 0.28f * std::abs(std::cos(u * kPi * 4.5f));
                    s.halfWidths.push_back(plen * 0.17f *
                                           std::pow(std::sin(kPi * std::min(u * 1.05f + 0.04f, 1.0f)), 0.55f) * lobes);
                }
                plant.push_back(std::move(s));
            }
        }
        plant.push_back({.points = rachis,
                         .halfWidths = widths(24, S * 0.005f, [](float t) { return 1.0f - 0.6f * t; }),
                         .base = dead ? deadBase * 0.8f : srgb(0.20f, 0.30f, 0.10f),
                         .tip = tip0,
                         .tipStart = 0.3f,
                         .shadeBase = 0.3f});
    }
    paintLitter(plant, dice, S, autumn ? 8 : 4); // a few leaves in front of the stems
    return plant;
}

// ---- flowers and shrubs ----------------------------------------------------------------------------------------

enum class FlowerForm { Daisy, Spike, Cup, Shrub };

struct FlowerStyle {
    FlowerForm form;
    vec3 petals; // linear
    vec3 centre;
};

// Cycles through the four forms so that any variant count shows all of them, and through flower colours so each
// row has yellow, white, purple and red heads.
FlowerStyle flowerStyle(uint32_t variant, Dice& dice) {
    static const FlowerForm kForms[] = {FlowerForm::Daisy, FlowerForm::Spike, FlowerForm::Cup, FlowerForm::Shrub};
    const vec3 kColours[] = {srgb(0.98f, 0.82f, 0.12f), srgb(0.56f, 0.30f, 0.78f), srgb(0.86f, 0.10f, 0.08f),
                             srgb(0.97f, 0.97f, 0.93f), srgb(0.97f, 0.96f, 0.94f), srgb(0.40f, 0.42f, 0.90f),
                             srgb(0.98f, 0.58f, 0.10f), srgb(0.92f, 0.38f, 0.60f)};
    const vec3 kCentres[] = {srgb(0.70f, 0.42f, 0.05f), srgb(0.56f, 0.30f, 0.78f), srgb(0.12f, 0.10f, 0.06f),
                             srgb(0.95f, 0.80f, 0.20f), srgb(0.96f, 0.76f, 0.10f), srgb(0.40f, 0.42f, 0.90f),
                             srgb(0.30f, 0.16f, 0.05f), srgb(0.95f, 0.85f, 0.30f)};
    const size_t c = variant % 8;
    // Beyond the first eight, colours are shifted a little so repeated styles are not identical.
    const float shift = variant >= 8 ? dice.range(0.85f, 1.1f) : 1.0f;
    return {kForms[variant % 4], glm::clamp(kColours[c] * shift, 0.0f, 1.0f), kCentres[c]};
}

void paintRosette(Plant& plant, Dice& dice, float S, int count) {
    const vec3 greens[] = {srgb(0.22f, 0.42f, 0.11f), srgb(0.30f, 0.50f, 0.15f), srgb(0.18f, 0.36f, 0.10f)};
    for (int i = 0; i < count; ++i) {
        const float a = dice.range(-1.3f, 1.3f);
        const float length = S * dice.range(0.18f, 0.34f) * (1.0f - 0.3f * std::abs(a));
        const vec3 c = dice.jitter(greens[size_t(dice() * 3.0f) % 3], 0.12f);
        Stroke s = leaf(vec2(S * 0.5f + dice.centred() * S * 0.04f, S), direction(a), length,
                        S * dice.range(0.024f, 0.038f), 0.25f, c * 0.8f, c * 1.15f);
        s.shadeBase = 0.4f;
        plant.push_back(std::move(s));
    }
}

// A slightly curved stem with a few leaves; returns its centreline so a flower head can be put on top.
std::vector<vec2> paintStem(Plant& plant, Dice& dice, float S, float height) {
    const vec2 base(S * 0.5f + dice.centred() * S * 0.07f, S);
    const float lean = dice.range(-0.35f, 0.35f), curve = dice.range(-0.25f, 0.25f);
    const auto points =
        cubicBezier(base, base + direction(lean * 0.5f) * height * 0.35f, base + direction(lean) * height * 0.7f,
                    base + direction(lean + curve) * height, 16);
    const vec3 green = dice.jitter(srgb(0.27f, 0.46f, 0.13f), 0.1f);
    plant.push_back({.points = points,
                     .halfWidths = widths(16, S * 0.0048f, [](float t) { return 1.0f - 0.4f * t; }),
                     .base = green * 0.8f,
                     .tip = green,
                     .tipStart = 0.0f,
                     .shadeBase = 0.3f});
    const int leaves = 1 + int(dice() * 3.0f);
    for (int i = 0; i < leaves; ++i) {
        const auto [at, tangent] = alongPolyline(points, dice.range(0.2f, 0.6f));
        const float side = i % 2 == 0 ? 1.0f : -1.0f;
        plant.push_back(leaf(at, rotate(tangent, side * dice.range(0.5f, 0.9f)), S * dice.range(0.08f, 0.13f),
                             S * 0.016f, 0.2f, green * 0.9f, green * 1.1f));
    }
    return points;
}

void paintDaisy(Plant& plant, Dice& dice, vec2 centre, float radius, const FlowerStyle& style) {
    // Seen from slightly above: the ring of petals is squashed vertically; the far petals are drawn first and
    // darker, the disc sits on top.
    const int petals = 12 + int(dice() * 5.0f);
    const float phase = dice.range(0.0f, 2.0f * kPi);
    for (int pass = 0; pass < 2; ++pass)
        for (int k = 0; k < petals; ++k) {
            const float a = phase + 2.0f * kPi * float(k) / float(petals);
            const vec2 d(std::cos(a), std::sin(a) * 0.45f);
            if ((d.y < 0.0f) != (pass == 0)) continue;
            const vec3 c = dice.jitter(style.petals, 0.06f) * (d.y < 0.0f ? 0.8f : 1.0f);
            Stroke s = leaf(centre + d * radius * 0.15f, glm::normalize(d), radius * glm::length(d) * 0.95f,
                            radius * 0.2f, 0.0f, c * 0.9f, c);
            s.midrib = 0.0f;
            plant.push_back(std::move(s));
        }
    plant.push_back(dot(centre, radius * 0.3f, style.centre, 0.7f));
}

void paintSpike(Plant& plant, Dice& dice, const std::vector<vec2>& stem, float S, const FlowerStyle& style) {
    const int florets = 16 + int(dice() * 8.0f);
    for (int i = 0; i < florets; ++i) {
        const float t = 0.62f + 0.38f * float(i) / float(florets - 1);
        const auto [at, tangent] = alongPolyline(stem, t);
        const float side = i % 2 == 0 ? 1.0f : -1.0f;
        const float radius = S * (0.02f - 0.01f * (t - 0.62f) / 0.38f);
        // The topmost florets are still buds: darker and greener.
        const float bud = smoothstep(0.85f, 1.0f, t);
        const vec3 c = glm::mix(dice.jitter(style.petals, 0.15f), srgb(0.35f, 0.40f, 0.20f), bud * 0.6f);
        plant.push_back(dot(at + vec2(-tangent.y, tangent.x) * side * radius * 0.7f, radius, c, 0.8f));
    }
}

void paintCup(Plant& plant, Dice& dice, vec2 centre, float radius, const FlowerStyle& style) {
    plant.push_back(dot(centre + vec2(0.0f, -radius * 0.25f), radius * 0.22f, style.centre));
    const float angles[] = {-1.05f, 1.05f, -0.5f, 0.5f, 0.0f}; // side petals first, the front petal last
    for (float a : angles) {
        const vec2 dir = direction(a + dice.range(-0.12f, 0.12f));
        const vec3 c = dice.jitter(style.petals, 0.08f) * (std::abs(a) > 0.8f ? 0.78f : 1.0f);
        Stroke s{.base = c * 0.55f, .tip = c, .tipStart = 0.0f, .sideShade = 0.2f};
        for (int i = 0; i < 8; ++i) {
            const float u = float(i) / 7.0f;
            s.points.push_back(centre + dir * (radius * u));
            s.halfWidths.push_back(radius * 0.42f * (0.3f + 0.7f * std::sin(0.5f * kPi * std::min(1.0f, u * 1.6f))));
        }
        plant.push_back(std::move(s));
    }
}

void paintShrub(Plant& plant, Dice& dice, float S, const FlowerStyle& style) {
    const vec2 centre(S * 0.5f, S * 0.58f);
    const float radius = S * dice.range(0.32f, 0.38f);
    const vec3 bark = srgb(0.36f, 0.26f, 0.16f);
    const int twigs = 5 + int(dice() * 4.0f);
    for (int i = 0; i < twigs; ++i) {
        const vec2 base(S * 0.5f + dice.centred() * S * 0.05f, S);
        const vec2 end = centre + direction(dice.range(-1.2f, 1.2f)) * radius * dice.range(0.5f, 0.9f);
        plant.push_back({.points = cubicBezier(base, glm::mix(base, end, 0.3f) + vec2(dice.centred() * S * 0.03f, 0),
                                               glm::mix(base, end, 0.7f), end, 10),
                         .halfWidths = widths(10, S * 0.007f, [](float t) { return 1.0f - 0.6f * t; }),
                         .base = bark * 0.8f,
                         .tip = bark,
                         .tipStart = 0.0f});
    }
    // Leaves fill a dome; those low and deep inside are darker (ambient occlusion of the canopy).
    const vec3 greens[] = {srgb(0.20f, 0.40f, 0.12f), srgb(0.28f, 0.48f, 0.14f), srgb(0.16f, 0.33f, 0.10f)};
    const int leaves = 230 + int(dice() * 60.0f);
    for (int i = 0; i < leaves; ++i) {
        vec2 u(dice.range(-1.0f, 1.0f), dice.range(-1.0f, 1.0f));
        if (glm::dot(u, u) > 1.0f) u *= 0.7f / glm::length(u);
        const vec2 at = centre + u * radius * vec2(1.0f, 0.9f);
        if (at.y > S * 0.97f) continue;
        const float light = 0.55f + 0.3f * (-u.y * 0.5f + 0.5f) + 0.25f * glm::length(u);
        const float length = S * dice.range(0.03f, 0.055f);
        const vec3 c = dice.jitter(greens[size_t(dice() * 3.0f) % 3], 0.12f) * light;
        const vec2 dir = rotate(glm::length(u) > 0.05f ? glm::normalize(u) : vec2(0, -1), dice.range(-0.9f, 0.9f));
        plant.push_back(leaf(at, dir, length, length * 0.3f, 0.1f, c * 0.9f, c * 1.1f));
    }
    const int blossoms = 18 + int(dice() * 12.0f);
    for (int i = 0; i < blossoms; ++i) {
        const float a = dice.range(-1.7f, 1.7f);
        const vec2 at = centre + direction(a) * radius * vec2(1.0f, 0.9f) * dice.range(0.55f, 0.95f);
        if (at.y > S * 0.93f) continue;
        const float r = S * dice.range(0.009f, 0.014f);
        for (int k = 0; k < 5; ++k) {
            const vec2 d = direction(2.0f * kPi * float(k) / 5.0f + a);
            const vec3 c = dice.jitter(style.petals, 0.08f);
            plant.push_back(dot(at + d * r * 0.8f, r * 0.6f, c));
        }
        plant.push_back(dot(at, r * 0.35f, style.centre));
    }
}

Plant paintFlowers(Dice& dice, float S, uint32_t variant) {
    Plant plant;
    const FlowerStyle style = flowerStyle(variant, dice);
    if (style.form == FlowerForm::Shrub) {
        paintShrub(plant, dice, S, style);
        return plant;
    }
    paintRosette(plant, dice, S, 11 + int(dice() * 6.0f));
    const int stems = style.form == FlowerForm::Cup ? 3 + int(dice() * 3.0f) : 4 + int(dice() * 4.0f);
    for (int i = 0; i < stems; ++i) {
        const float height = S * dice.range(0.5f, 0.9f);
        const auto stem = paintStem(plant, dice, S, height);
        const vec2 top = stem.back();
        switch (style.form) {
        case FlowerForm::Daisy:
            paintDaisy(plant, dice, top, S * dice.range(0.05f, 0.075f), style);
            break;
        case FlowerForm::Spike:
            paintSpike(plant, dice, stem, S, style);
            break;
        case FlowerForm::Cup:
            paintCup(plant, dice, top, S * dice.range(0.065f, 0.09f), style);
            break;
        case FlowerForm::Shrub:
            break;
        }
    }
    return plant;
}

// ---------------------------------------------------------------------------------------------------------------
// Texel helpers

struct Rgba8View {
    uint8_t* data;
    uint32_t width;
    uint8_t* at(uint32_t x, uint32_t y) const { return data + (size_t(y) * width + x) * 4; }
};

void bleedCell(const Rgba8View& image, const AtlasRect& cell) {
    const uint32_t w = cell.width, h = cell.height;
    std::vector<uint32_t> distance(size_t(w) * h, UINT32_MAX);
    std::vector<uint32_t> queue;
    queue.reserve(distance.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            if (image.at(cell.x + x, cell.y + y)[3] != 0) {
                distance[size_t(y) * w + x] = 0;
                queue.push_back(y * w + x);
            }
    if (queue.empty()) return; // nothing to bleed from; the cell's colour never shows
    // Breadth-first from the visible texels: a texel is reached only after every texel one step closer, so its
    // colour can be the mean of those neighbours. The result is smooth and depends only on the image.
    for (size_t head = 0; head < queue.size(); ++head) {
        const uint32_t x = queue[head] % w, y = queue[head] / w, d = distance[queue[head]];
        if (d > 0) {
            uint32_t sum[3] = {0, 0, 0}, count = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = int(x) + dx, ny = int(y) + dy;
                    if (nx < 0 || ny < 0 || nx >= int(w) || ny >= int(h)) continue;
                    if (distance[size_t(ny) * w + size_t(nx)] != d - 1) continue;
                    const uint8_t* n = image.at(cell.x + uint32_t(nx), cell.y + uint32_t(ny));
                    for (int c = 0; c < 3; ++c) sum[c] += n[c];
                    ++count;
                }
            uint8_t* t = image.at(cell.x + x, cell.y + y);
            for (int c = 0; c < 3; ++c) t[c] = uint8_t((sum[c] + count / 2) / count);
        }
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = int(x) + dx, ny = int(y) + dy;
                if (nx < 0 || ny < 0 || nx >= int(w) || ny >= int(h)) continue;
                uint32_t& nd = distance[size_t(ny) * w + size_t(nx)];
                if (nd != UINT32_MAX) continue;
                nd = d + 1;
                queue.push_back(uint32_t(ny) * w + uint32_t(nx));
            }
    }
}

bool isPowerOfTwo(uint64_t v) {
    return v != 0 && (v & (v - 1)) == 0;
}

void validateDesc(const AtlasDesc& desc, const std::string& source) {
    require(isPowerOfTwo(desc.cellWidth) && isPowerOfTwo(desc.cellHeight) && desc.cellWidth >= 4 &&
                desc.cellHeight >= 4 && desc.cellWidth <= 4096 && desc.cellHeight <= 4096,
            source + ": atlas cell size " + std::to_string(desc.cellWidth) + "x" + std::to_string(desc.cellHeight) +
                " must be powers of two from 4 to 4096 (so every mip level keeps whole cells)");
    require(!desc.rows.empty() && desc.rows.size() <= 64, source + ": an atlas needs 1..64 rows");
    for (const AtlasRow& row : desc.rows)
        require(!row.cells.empty() && row.cells.size() <= 64,
                source + ": atlas row '" + row.category + "' must have 1..64 columns");
    require(uint64_t(desc.width()) <= kMaxImageEdge && uint64_t(desc.height()) <= kMaxImageEdge,
            source + ": atlas image would be " + std::to_string(desc.width()) + "x" + std::to_string(desc.height()) +
                " texels, more than " + std::to_string(kMaxImageEdge) + " per edge");
}

} // namespace

// ---------------------------------------------------------------------------------------------------------------
// Generation

AtlasPlantKind atlasPlantKindForCategory(const std::string& category) {
    std::string name = category;
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (name.find("grass") != std::string::npos) return AtlasPlantKind::Grass;
    if (name.find("fern") != std::string::npos || name.find("forest") != std::string::npos)
        return AtlasPlantKind::Ferns;
    return AtlasPlantKind::Flowers;
}

std::vector<AtlasRowSpec> defaultAtlasRows(uint32_t variantsOverride) {
    const VegetationParams defaults;
    std::vector<AtlasRowSpec> rows;
    for (uint32_t i = 0; i < defaults.categoryCount; ++i) {
        const VegetationCategory& category = defaults.categories[i];
        rows.push_back({.category = category.name,
                        .kind = atlasPlantKindForCategory(category.name),
                        .columns = variantsOverride > 0 ? variantsOverride : category.variants});
    }
    return rows;
}

Atlas generateAtlas(const AtlasGenParams& params) {
    require(isPowerOfTwo(params.cellSize) && params.cellSize >= 32 && params.cellSize <= 2048,
            "atlas cell size " + std::to_string(params.cellSize) + " must be a power of two from 32 to 2048");
    Atlas atlas;
    atlas.desc.cellWidth = atlas.desc.cellHeight = params.cellSize;
    for (const AtlasRowSpec& spec : params.rows) {
        require(spec.columns >= 1 && spec.columns <= 64, "atlas row '" + spec.category + "' has " +
                                                             std::to_string(spec.columns) +
                                                             " variants; it must have 1..64");
        atlas.desc.rows.push_back({.category = spec.category, .cells = std::vector<AtlasCell>(spec.columns)});
    }
    validateDesc(atlas.desc, "generated atlas");

    const AtlasDesc& desc = atlas.desc;
    AtlasMip& image = atlas.mips.emplace_back(AtlasMip{desc.width(), desc.height(), {}});
    image.rgba.assign(size_t(image.width) * image.height * 4, 0);
    const float S = float(params.cellSize);
    for (uint32_t r = 0; r < desc.rows.size(); ++r) {
        const AtlasPlantKind kind = params.rows[r].kind;
        for (uint32_t c = 0; c < desc.rows[r].cells.size(); ++c) {
            // Keyed by (seed, kind, variant), not by row index: reordering rows does not repaint the plants.
            const uint64_t key = hashKey({params.seed, 0x61746c6173ull /* "atlas" */, uint64_t(kind), c});
            Dice dice{HashStream{key}};
            Plant plant = kind == AtlasPlantKind::Grass   ? paintGrass(dice, S, c)
                          : kind == AtlasPlantKind::Ferns ? paintFerns(dice, S, c)
                                                          : paintFlowers(dice, S, c);
            fitInCell(plant, S, std::max(2.0f, S * 0.02f));
            CellCanvas canvas(params.cellSize, hashKey({key, 1}));
            for (const Stroke& stroke : plant) canvas.draw(stroke);

            const AtlasRect rect = desc.cellRect(r, c);
            for (uint32_t y = 0; y < rect.height; ++y)
                for (uint32_t x = 0; x < rect.width; ++x) {
                    const vec4 p = canvas.texel(x, y);
                    uint8_t* t = &image.rgba[((size_t(rect.y) + y) * image.width + rect.x + x) * 4];
                    const vec3 straight = p.a > 0.0f ? vec3(p) / p.a : vec3(0.0f);
                    for (int k = 0; k < 3; ++k) t[k] = encodeSrgb(straight[k]);
                    t[3] = encodeUnorm(p.a);
                }
        }
    }
    bleedColours(atlas);
    return atlas;
}

void bleedColours(Atlas& atlas) {
    require(!atlas.mips.empty(), "bleedColours: the atlas has no image");
    AtlasMip& image = atlas.mips[0];
    const Rgba8View view{image.rgba.data(), image.width};
    for (uint32_t r = 0; r < atlas.desc.rows.size(); ++r)
        for (uint32_t c = 0; c < atlas.desc.rows[r].cells.size(); ++c) bleedCell(view, atlas.desc.cellRect(r, c));
}

// ---------------------------------------------------------------------------------------------------------------
// Mipmaps

float alphaCoverage(const AtlasMip& mip, const AtlasRect& rect, float reference) {
    if (rect.width == 0 || rect.height == 0) return 0.0f;
    size_t passing = 0;
    for (uint32_t y = rect.y; y < rect.y + rect.height; ++y)
        for (uint32_t x = rect.x; x < rect.x + rect.width; ++x)
            passing += float(mip.rgba[(size_t(y) * mip.width + x) * 4 + 3]) / 255.0f >= reference;
    return float(passing) / float(size_t(rect.width) * rect.height);
}

namespace {

// Fraction of alphas that pass the reference after scaling and 8-bit quantisation, exactly as alphaCoverage()
// will measure the stored level.
float scaledCoverage(const std::vector<float>& alphas, float scale, float reference) {
    size_t passing = 0;
    for (float a : alphas) passing += float(encodeUnorm(a * scale)) / 255.0f >= reference;
    return float(passing) / float(alphas.size());
}

// Alpha scale for one cell of one level that brings its coverage closest to `target` (bisection: coverage only
// grows with the scale).
float coverageScale(const std::vector<float>& alphas, float target, float reference) {
    if (target <= 0.0f) return 1.0f;
    float lo = 0.0f, hi = 1.0f;
    while (scaledCoverage(alphas, hi, reference) < target && hi < 1024.0f) lo = hi, hi *= 2.0f;
    for (int i = 0; i < 24; ++i) {
        const float mid = 0.5f * (lo + hi);
        (scaledCoverage(alphas, mid, reference) < target ? lo : hi) = mid;
    }
    const float below = scaledCoverage(alphas, lo, reference), above = scaledCoverage(alphas, hi, reference);
    const float best = std::min(target - below, above - target);
    // Many scales reach the same coverage; leave alpha alone when the level already matches as well as any scale
    // could (a solid cell stays solid instead of dropping to just above the reference).
    if (std::abs(scaledCoverage(alphas, 1.0f, reference) - target) <= best) return 1.0f;
    return target - below < above - target ? lo : hi;
}

} // namespace

void buildMipChain(Atlas& atlas, float alphaReference, bool preserveCoverage) {
    const AtlasDesc& desc = atlas.desc;
    require(!atlas.mips.empty() && atlas.mips[0].width == desc.width() && atlas.mips[0].height == desc.height() &&
                atlas.mips[0].rgba.size() == size_t(desc.width()) * desc.height() * 4,
            "buildMipChain: the atlas image does not match its description");
    atlas.mips.resize(1);
    const auto& toLinear = srgbTable().toLinear;

    // The chain is filtered from unscaled float levels; coverage scaling only touches the stored bytes, so one
    // level's scale never compounds into the next.
    uint32_t w = desc.width(), h = desc.height();
    std::vector<vec4> level(size_t(w) * h);
    for (size_t i = 0; i < level.size(); ++i) {
        const uint8_t* t = &atlas.mips[0].rgba[i * 4];
        level[i] = vec4(toLinear[t[0]], toLinear[t[1]], toLinear[t[2]], float(t[3]) / 255.0f);
    }

    const uint32_t columns = desc.maxColumns();
    for (uint32_t l = 1; l < desc.mipLevelCount(); ++l) {
        // Cells are powers of two and aligned, so a 2x2 box never straddles two cells.
        const uint32_t nw = w / 2, nh = h / 2;
        std::vector<vec4> next(size_t(nw) * nh);
        for (uint32_t y = 0; y < nh; ++y)
            for (uint32_t x = 0; x < nw; ++x) {
                const vec4 s[4] = {level[size_t(2 * y) * w + 2 * x], level[size_t(2 * y) * w + 2 * x + 1],
                                   level[size_t(2 * y + 1) * w + 2 * x], level[size_t(2 * y + 1) * w + 2 * x + 1]};
                vec3 weighted(0.0f), plain(0.0f);
                float alpha = 0.0f;
                for (const vec4& v : s) weighted += vec3(v) * v.a, plain += vec3(v), alpha += v.a;
                next[size_t(y) * nw + x] = vec4(alpha > 0.0f ? weighted / alpha : plain * 0.25f, alpha * 0.25f);
            }
        level = std::move(next);
        w = nw, h = nh;

        AtlasMip& mip = atlas.mips.emplace_back(AtlasMip{w, h, std::vector<uint8_t>(size_t(w) * h * 4)});
        for (uint32_t r = 0; r < desc.rows.size(); ++r)
            for (uint32_t c = 0; c < columns; ++c) {
                const AtlasRect cell = desc.cellRect(r, c, l);
                std::vector<float> alphas;
                alphas.reserve(size_t(cell.width) * cell.height);
                for (uint32_t y = cell.y; y < cell.y + cell.height; ++y)
                    for (uint32_t x = cell.x; x < cell.x + cell.width; ++x)
                        alphas.push_back(level[size_t(y) * w + x].a);
                const float target = alphaCoverage(atlas.mips[0], desc.cellRect(r, c, 0), alphaReference);
                const float scale = preserveCoverage ? coverageScale(alphas, target, alphaReference) : 1.0f;
                for (uint32_t y = cell.y; y < cell.y + cell.height; ++y)
                    for (uint32_t x = cell.x; x < cell.x + cell.width; ++x) {
                        const vec4& v = level[size_t(y) * w + x];
                        uint8_t* t = &mip.rgba[(size_t(y) * w + x) * 4];
                        for (int k = 0; k < 3; ++k) t[k] = encodeSrgb(v[k]);
                        t[3] = encodeUnorm(v.a * scale);
                    }
            }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Files

namespace {

using nlohmann::json;

void requireKeys(const json& object, std::initializer_list<const char*> allowed, const std::string& where) {
    for (const auto& [key, value] : object.items()) {
        bool known = false;
        for (const char* name : allowed) known = known || key == name;
        require(known, where + ": unknown key '" + key + "'");
    }
}

float readNumber(const json& object, const char* key, float fallback, float lo, float hi, const std::string& where) {
    if (!object.contains(key)) return fallback;
    const json& v = object[key];
    require(v.is_number() && v.get<double>() >= lo && v.get<double>() <= hi,
            where + ": '" + key + "' must be a number in [" + json(lo).dump() + ", " + json(hi).dump() + "]");
    return v.get<float>();
}

AtlasDesc parseAtlasDesc(const json& j, const std::string& source) {
    const std::string where = "atlas description '" + source + "'";
    require(j.is_object(), where + ": the top level must be a JSON object");
    requireKeys(j, {"format", "version", "cell_size", "base_u", "base_v", "aspect", "rows"}, where);
    require(!j.contains("format") || j["format"] == "sward-atlas", where + ": 'format' must be \"sward-atlas\"");
    require(!j.contains("version") || j["version"] == 1, where + ": 'version' must be 1");

    AtlasDesc desc;
    require(j.contains("cell_size") && j["cell_size"].is_array() && j["cell_size"].size() == 2 &&
                j["cell_size"][0].is_number_unsigned() && j["cell_size"][1].is_number_unsigned(),
            where + ": 'cell_size' must be [width, height] in texels");
    desc.cellWidth = uint32_t(std::min<uint64_t>(j["cell_size"][0].get<uint64_t>(), UINT32_MAX));
    desc.cellHeight = uint32_t(std::min<uint64_t>(j["cell_size"][1].get<uint64_t>(), UINT32_MAX));

    const AtlasCell defaults{.baseU = readNumber(j, "base_u", 0.5f, 0.0f, 1.0f, where),
                             .baseV = readNumber(j, "base_v", 1.0f, 0.0f, 1.0f, where),
                             .aspect = readNumber(j, "aspect", 1.0f, 0.01f, 100.0f, where)};
    require(j.contains("rows") && j["rows"].is_array() && !j["rows"].empty(),
            where + ": 'rows' must be a non-empty array");
    for (size_t r = 0; r < j["rows"].size(); ++r) {
        const json& row = j["rows"][r];
        const std::string rowWhere = where + " row " + std::to_string(r);
        require(row.is_object(), rowWhere + ": must be an object");
        requireKeys(row, {"category", "columns", "cells"}, rowWhere);
        require(row.contains("category") && row["category"].is_string(), rowWhere + ": 'category' must be a string");
        require(row.contains("columns") && row["columns"].is_number_unsigned() && row["columns"].get<uint64_t>() >= 1 &&
                    row["columns"].get<uint64_t>() <= 64,
                rowWhere + ": 'columns' must be an integer in 1..64");
        AtlasRow& out = desc.rows.emplace_back(AtlasRow{row["category"].get<std::string>(), {}});
        out.cells.assign(row["columns"].get<size_t>(), defaults);
        if (!row.contains("cells")) continue;
        require(row["cells"].is_array() && row["cells"].size() == out.cells.size(),
                rowWhere + ": 'cells' must be an array with one entry per column");
        for (size_t c = 0; c < out.cells.size(); ++c) {
            const json& cell = row["cells"][c];
            const std::string cellWhere = rowWhere + " cell " + std::to_string(c);
            require(cell.is_object(), cellWhere + ": must be an object");
            requireKeys(cell, {"base_u", "base_v", "aspect"}, cellWhere);
            out.cells[c] = {.baseU = readNumber(cell, "base_u", defaults.baseU, 0.0f, 1.0f, cellWhere),
                            .baseV = readNumber(cell, "base_v", defaults.baseV, 0.0f, 1.0f, cellWhere),
                            .aspect = readNumber(cell, "aspect", defaults.aspect, 0.01f, 100.0f, cellWhere)};
        }
    }
    validateDesc(desc, where);
    return desc;
}

json describe(const AtlasDesc& desc) {
    json rows = json::array();
    for (const AtlasRow& row : desc.rows) {
        json cells = json::array();
        for (const AtlasCell& c : row.cells)
            cells.push_back({{"base_u", c.baseU}, {"base_v", c.baseV}, {"aspect", c.aspect}});
        rows.push_back({{"category", row.category}, {"columns", row.cells.size()}, {"cells", cells}});
    }
    return {
        {"format", "sward-atlas"}, {"version", 1}, {"cell_size", {desc.cellWidth, desc.cellHeight}}, {"rows", rows}};
}

// Replaces `path` by the finished temporary file, so readers never see a half-written atlas.
void commitFile(const std::string& tmp, const std::string& path) {
    std::error_code error;
    std::filesystem::rename(tmp, path, error);
    if (error) {
        std::filesystem::remove(tmp, error);
        throw Error("cannot write '" + path + "': rename from '" + tmp + "' failed");
    }
}

} // namespace

Atlas loadAtlas(const std::string& pngPath, const std::string& jsonPath) {
    std::ifstream file(jsonPath);
    require(file.good(), "cannot open atlas description '" + jsonPath + "': file missing or unreadable");
    json j;
    try {
        j = json::parse(file);
    } catch (const json::exception& e) {
        throw Error("atlas description '" + jsonPath + "' is not valid JSON: " + e.what());
    }
    Atlas atlas{.desc = parseAtlasDesc(j, jsonPath), .mips = {}};

    const ImageData image = loadImage(pngPath);
    require(image.channels == 4 && image.bitDepth == 8,
            "atlas image '" + pngPath + "' must be an 8-bit RGBA PNG (it has " + std::to_string(image.channels) +
                " channels of " + std::to_string(image.bitDepth) + " bits)");
    const AtlasDesc& desc = atlas.desc;
    require(image.width == desc.width() && image.height == desc.height(),
            "atlas image '" + pngPath + "' is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                " but '" + jsonPath + "' describes " + std::to_string(desc.maxColumns()) + " columns x " +
                std::to_string(desc.rows.size()) + " rows of " + std::to_string(desc.cellWidth) + "x" +
                std::to_string(desc.cellHeight) + " cells = " + std::to_string(desc.width()) + "x" +
                std::to_string(desc.height()));
    AtlasMip& mip = atlas.mips.emplace_back(AtlasMip{image.width, image.height, {}});
    mip.rgba.resize(image.samples.size());
    // loadImage() normalised each byte b to b / 255; rounding recovers it exactly.
    for (size_t i = 0; i < image.samples.size(); ++i) mip.rgba[i] = uint8_t(image.samples[i] * 255.0f + 0.5f);
    return atlas;
}

void saveAtlas(const Atlas& atlas, const std::string& pngPath, const std::string& jsonPath) {
    const AtlasDesc& desc = atlas.desc;
    validateDesc(desc, "saveAtlas('" + jsonPath + "')");
    require(!atlas.mips.empty() && atlas.mips[0].width == desc.width() && atlas.mips[0].height == desc.height() &&
                atlas.mips[0].rgba.size() == size_t(desc.width()) * desc.height() * 4,
            "cannot write '" + pngPath + "': the atlas image does not match its description");

    const std::string pngTmp = pngPath + ".tmp";
    const AtlasMip& image = atlas.mips[0];
    if (!stbi_write_png(pngTmp.c_str(), int(image.width), int(image.height), 4, image.rgba.data(),
                        int(image.width * 4)))
        throw Error("cannot write atlas image '" + pngPath + "' (is the folder writable?)");
    commitFile(pngTmp, pngPath);

    const std::string jsonTmp = jsonPath + ".tmp";
    {
        std::ofstream out(jsonTmp);
        out << describe(desc).dump(2) << "\n";
        require(out.good(), "cannot write atlas description '" + jsonPath + "' (is the folder writable?)");
    }
    commitFile(jsonTmp, jsonPath);
}

} // namespace sward
