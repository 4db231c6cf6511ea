// The procedural plant painters of the built-in atlas: grass clumps, ferns over leaf litter, flowers and shrubs.
#include "vegetation/atlas_paint.h"

namespace sward::atlas_detail {

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

} // namespace sward::atlas_detail
