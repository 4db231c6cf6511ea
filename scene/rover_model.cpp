#include "scene/rover_model.h"

#include "common/atomic_file.h"
#include "common/error.h"

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

namespace sward {

namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

using json = nlohmann::ordered_json; // keeps the key order as written: stable, readable files
using Vec = glm::dvec3;

// One glTF primitive under construction, in its node's glTF frame (+Y up).
struct Part {
    int material = 0;
    std::vector<glm::vec3> positions, normals;
    std::vector<uint16_t> indices;

    uint16_t vertex(Vec p, Vec n) {
        positions.push_back(glm::vec3(p));
        normals.push_back(glm::vec3(glm::normalize(n)));
        return uint16_t(positions.size() - 1);
    }
    // Triangle whose front (counter-clockwise side, glTF convention) faces `outward`.
    void triangle(Vec a, Vec b, Vec c, Vec na, Vec nb, Vec nc, Vec outward) {
        if (glm::dot(glm::cross(b - a, c - a), outward) < 0.0) {
            std::swap(b, c);
            std::swap(nb, nc);
        }
        indices.insert(indices.end(), {vertex(a, na), vertex(b, nb), vertex(c, nc)});
    }
    // Flat quad a-b-c-d (in order around its edge) facing `n`.
    void quad(Vec a, Vec b, Vec c, Vec d, Vec n) {
        triangle(a, b, c, n, n, n, n);
        triangle(a, c, d, n, n, n, n);
    }
};

Vec axisVector(int axis, double length = 1.0) {
    Vec v(0.0);
    v[axis] = length;
    return v;
}

void box(Part& part, Vec centre, Vec half) {
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            const Vec n = axisVector(axis, side), f = centre + n * half[axis];
            const Vec u = axisVector((axis + 1) % 3, half[(axis + 1) % 3]),
                      v = axisVector((axis + 2) % 3, half[(axis + 2) % 3]);
            part.quad(f - u - v, f + u - v, f + u + v, f - u + v, n);
        }
}

// Point k of 16 around the unit circle, (cos, sin) of k * 22.5 degrees from square roots only: correctly
// rounded everywhere, so the file's bytes do not depend on the C library's sin/cos.
constexpr int kSegments = 16;
glm::dvec2 circle(int k) {
    const double s2 = std::sqrt(2.0), a = std::sqrt(2.0 - s2) / 2.0, b = s2 / 2.0, d = std::sqrt(2.0 + s2) / 2.0;
    const std::array<glm::dvec2, 4> quarter{glm::dvec2(1.0, 0.0), glm::dvec2(d, a), glm::dvec2(b, b), glm::dvec2(a, d)};
    k = ((k % kSegments) + kSegments) % kSegments;
    glm::dvec2 p = quarter[size_t(k % 4)];
    for (int q = 0; q < k / 4; ++q) p = glm::dvec2(-p.y, p.x); // exact quarter turns
    return p;
}

// Point of a circle of `radius` around `centre` in the plane normal to `axis`.
Vec ringPoint(Vec centre, int axis, double radius, int k) {
    const glm::dvec2 c = circle(k);
    return centre + axisVector((axis + 1) % 3, radius * c.x) + axisVector((axis + 2) % 3, radius * c.y);
}

// Side of a cylinder along `axis` (smooth radial normals).
void tube(Part& part, Vec centre, int axis, double radius, double halfLength) {
    const Vec h = axisVector(axis, halfLength);
    for (int k = 0; k < kSegments; ++k) {
        const Vec p0 = ringPoint(centre, axis, radius, k), p1 = ringPoint(centre, axis, radius, k + 1);
        const Vec n0 = p0 - centre, n1 = p1 - centre, outward = n0 + n1;
        part.triangle(p0 - h, p1 - h, p1 + h, n0, n1, n1, outward);
        part.triangle(p0 - h, p1 + h, p0 + h, n0, n1, n0, outward);
    }
}

// Flat annulus (inner > 0) or disc (inner = 0) around `centre`, facing axis * side.
void ring(Part& part, Vec centre, int axis, double side, double outer, double inner) {
    const Vec n = axisVector(axis, side);
    for (int k = 0; k < kSegments; ++k) {
        const Vec o0 = ringPoint(centre, axis, outer, k), o1 = ringPoint(centre, axis, outer, k + 1);
        if (inner <= 0.0) {
            part.triangle(centre, o0, o1, n, n, n, n);
        } else {
            part.quad(o0, o1, ringPoint(centre, axis, inner, k + 1), ringPoint(centre, axis, inner, k), n);
        }
    }
}

std::string base64(const std::vector<uint8_t>& data) {
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((data.size() + 2) / 3 * 4);
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t n = uint32_t(data[i]) << 16 | (i + 1 < data.size() ? uint32_t(data[i + 1]) << 8 : 0u) |
                           (i + 2 < data.size() ? uint32_t(data[i + 2]) : 0u);
        out += alphabet[n >> 18 & 63];
        out += alphabet[n >> 12 & 63];
        out += i + 1 < data.size() ? alphabet[n >> 6 & 63] : '=';
        out += i + 2 < data.size() ? alphabet[n & 63] : '=';
    }
    return out;
}

// Accumulates the glTF arrays and the one binary buffer.
struct Document {
    json materials = json::array(), meshes = json::array(), accessors = json::array(), views = json::array();
    std::vector<uint8_t> buffer;

    int material(const char* name, glm::dvec3 linear, double roughness) {
        materials.push_back({{"name", name},
                             {"pbrMetallicRoughness",
                              {{"baseColorFactor", {linear.r, linear.g, linear.b, 1.0}},
                               {"metallicFactor", 0.0},
                               {"roughnessFactor", roughness}}}});
        return int(materials.size() - 1);
    }

    int view(const void* data, size_t bytes, int target) {
        while (buffer.size() % 4) buffer.push_back(0); // accessor alignment
        const size_t offset = buffer.size();
        buffer.resize(offset + bytes);
        std::memcpy(buffer.data() + offset, data, bytes);
        views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
        return int(views.size() - 1);
    }

    int vec3Accessor(const std::vector<glm::vec3>& values, bool bounds) {
        json a = {{"bufferView", view(values.data(), values.size() * sizeof(glm::vec3), 34962)},
                  {"componentType", 5126},
                  {"count", values.size()},
                  {"type", "VEC3"}};
        if (bounds) { // required for POSITION by the glTF spec
            glm::vec3 lo = values.front(), hi = values.front();
            for (const glm::vec3& v : values) {
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
            a["min"] = {double(lo.x), double(lo.y), double(lo.z)};
            a["max"] = {double(hi.x), double(hi.y), double(hi.z)};
        }
        accessors.push_back(a);
        return int(accessors.size() - 1);
    }

    int mesh(const char* name, const std::vector<Part>& parts) {
        json primitives = json::array();
        for (const Part& part : parts) {
            const int position = vec3Accessor(part.positions, true), normal = vec3Accessor(part.normals, false);
            accessors.push_back({{"bufferView", view(part.indices.data(), part.indices.size() * 2, 34963)},
                                 {"componentType", 5123},
                                 {"count", part.indices.size()},
                                 {"type", "SCALAR"}});
            primitives.push_back({{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
                                  {"indices", int(accessors.size() - 1)},
                                  {"material", part.material},
                                  {"mode", 4}});
        }
        meshes.push_back({{"name", name}, {"primitives", primitives}});
        return int(meshes.size() - 1);
    }
};

// Translations rounded to 0.1 mm so the file reads 0.145, not 0.14499999999999996.
double tidy(double metres) {
    return std::round(metres * 1e4) / 1e4;
}

json node(const char* name, Vec translation, int mesh = -1, std::vector<int> children = {}) {
    json n = {{"name", name}, {"translation", {tidy(translation.x), tidy(translation.y), tidy(translation.z)}}};
    if (mesh >= 0) n["mesh"] = mesh;
    if (!children.empty()) n["children"] = children;
    return n;
}

} // namespace

std::string roverGltf(const RoverDimensions& d) {
    require(d.wheelRadius > 0.05 && d.wheelWidth > 0.02 && d.trackWidth > d.wheelWidth + 0.2 &&
                d.wheelBase > 2.0 * d.wheelRadius && d.cameraHeight > 0.4 && d.cameraBaseline > 0.0 &&
                d.cameraBaseline < 0.19,
            "rover dimensions out of range");
    Document doc;
    const int body = doc.material("body", {0.80, 0.30, 0.04}, 0.5);
    const int deck = doc.material("deck", {0.05, 0.06, 0.07}, 0.4);
    const int trim = doc.material("trim", {0.03, 0.03, 0.03}, 0.8);
    const int metal = doc.material("mast", {0.45, 0.46, 0.48}, 0.4);
    const int tyre = doc.material("tyre", {0.025, 0.025, 0.025}, 0.9);
    const int hub = doc.material("hub", {0.55, 0.55, 0.50}, 0.4);
    const int head = doc.material("camera", {0.12, 0.12, 0.13}, 0.5);
    const int lens = doc.material("lens", {0.01, 0.01, 0.02}, 0.1);

    // glTF frame of the rover: x left, y up, z forward; the origin on the ground at the centre.
    const double halfTrack = 0.5 * d.trackWidth, halfBase = 0.5 * d.wheelBase, r = d.wheelRadius;
    const double chassisY = 0.22;                                   // body centre height
    const double bodyHalfX = halfTrack - 0.5 * d.wheelWidth - 0.01; // 1 cm clear of the wheels
    const double deckTop = 0.11;                                    // above the chassis origin

    Part bodyPart{body}, deckPart{deck}, trimPart{trim};
    box(bodyPart, {0.0, 0.0, 0.0}, {bodyHalfX, 0.09, 0.45});
    box(deckPart, {0.0, 0.10, -0.03}, {bodyHalfX - 0.02, 0.01, 0.36});
    for (double z : {-1.0, 1.0}) box(trimPart, {0.0, -0.03, z * 0.465}, {bodyHalfX - 0.01, 0.03, 0.015});
    for (double x : {-1.0, 1.0})
        for (double z : {-1.0, 1.0}) // axle stubs from inside the body to the wheel's inner face
            box(trimPart, {x * (bodyHalfX - 0.0025), r - chassisY, z * halfBase}, {0.0125, 0.025, 0.025});
    const int chassisMesh = doc.mesh("chassis", {bodyPart, deckPart, trimPart});

    const double mastHeight = d.cameraHeight - 0.025 - (chassisY + deckTop); // up to the camera head's bottom
    Part mastPart{metal};
    box(mastPart, {0.0, 0.5 * mastHeight, 0.0}, {0.02, 0.5 * mastHeight, 0.02});
    const int mastMesh = doc.mesh("mast", {mastPart});

    Part headPart{head}, lensPart{lens};
    box(headPart, {0.0, 0.0, -0.03}, {0.10, 0.025, 0.03});
    for (double x : {-0.5, 0.5}) {
        const Vec centre(x * d.cameraBaseline, 0.0, 0.005);
        tube(lensPart, centre, 2, 0.015, 0.005);
        ring(lensPart, centre + Vec(0.0, 0.0, 0.005), 2, 1.0, 0.015, 0.0);
    }
    const int headMesh = doc.mesh("camera_head", {headPart, lensPart});

    const double halfWidth = 0.5 * d.wheelWidth, hubRadius = 0.55 * r;
    Part tyrePart{tyre}, hubPart{hub};
    tube(tyrePart, {0.0, 0.0, 0.0}, 0, r, halfWidth);
    for (double side : {-1.0, 1.0}) {
        ring(tyrePart, {side * halfWidth, 0.0, 0.0}, 0, side, r, hubRadius);
        ring(hubPart, {side * halfWidth, 0.0, 0.0}, 0, side, hubRadius, 0.0);
    }
    const int wheelMesh = doc.mesh("wheel", {tyrePart, hubPart});

    // Node indices are fixed by this order.
    json nodes = json::array();
    nodes.push_back(node("rover", {0.0, 0.0, 0.0}, -1, {1}));
    nodes.push_back(node("chassis", {0.0, chassisY, 0.0}, chassisMesh, {2, 4, 5, 6, 7}));
    nodes.push_back(node("mast", {0.0, deckTop, d.cameraForward}, mastMesh, {3}));
    nodes.push_back(node("camera_mount", {0.0, d.cameraHeight - (chassisY + deckTop), 0.0}, headMesh));
    const char* wheels[] = {"wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr"};
    for (int w = 0; w < 4; ++w) // front = +z, left = +x
        nodes.push_back(node(wheels[w],
                             {(w % 2 == 0 ? 1.0 : -1.0) * halfTrack, r - chassisY, (w < 2 ? 1.0 : -1.0) * halfBase},
                             wheelMesh));

    json gltf = {
        {"asset", {{"version", "2.0"}, {"generator", "sward-rover (sward, vegetation/rover_model.cpp)"}}},
        {"scene", 0},
        {"scenes", {{{"name", "rover"}, {"nodes", {0}}}}},
        {"nodes", nodes},
        {"meshes", doc.meshes},
        {"materials", doc.materials},
        {"accessors", doc.accessors},
        {"bufferViews", doc.views},
        {"buffers",
         {{{"byteLength", doc.buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(doc.buffer)}}}},
    };
    return gltf.dump(1) + "\n";
}

void saveRoverGltf(const std::string& path, const RoverDimensions& dimensions) {
    writeTextAtomically(path, roverGltf(dimensions));
}

} // namespace sward
