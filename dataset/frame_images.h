// Host copy of one rendered frame: what the renderer reads back and the dataset writer stores.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace sward {

struct FrameImages {
    uint32_t width = 0, height = 0;
    std::vector<uint16_t> rgbaHalf; // width*height*4 half floats, top row first
    std::vector<float> depth;       // planar metres, +inf where nothing was hit
    std::vector<uint32_t> labels;   // (semantic class << 24) | instance id, see gpu::kSemantic*
    std::vector<uint32_t> tiles;    // worlds of several tiles only: the plant's tile label (y * tilesX + x + 1) per
                                    // pixel, 0 where no plant is; instance ids count within a tile
    std::vector<float> normals;     // width*height*3: the drawn triangle's unit normal in the camera frame (x right,
                                    // y down, z forward), facing the camera; 0,0,0 where nothing was hit
    std::vector<uint16_t> rightRgbaHalf; // stereo only: the right view's colour
    std::vector<float> rightDepth;       // stereo only: the right view's truth pass, as depth
    std::vector<uint32_t> rightLabels;   // stereo only: the right view's truth pass, as labels
    std::vector<float> rightNormals;     // stereo only: the right view's truth pass, as normals (in the right
                                         // camera's axes, which are the left's: the rig is rectified)
    // An unsynchronised rig (camera.sensor.stereo_offset_s): the right view above is the rig's at the right camera's
    // time. Each view's occlusion mask is the rig's at that view's own time, so these are the other camera's depth
    // then: the right's at the left's time, the left's at the right's. Empty for a synchronised rig.
    std::vector<float> rightDepthAtLeftTime, leftDepthAtRightTime;
    // Motion ground truth (render.flow), width*height*4 floats per view: the flow of each pixel's surface point to the
    // next and to the previous tick: x, y pixels (target pixel centre minus this pixel's), z the point's planar depth
    // in that tick's camera, w 1 (0 where the pixel shows sky).
    std::vector<float> flowForward, flowBackward, rightFlowForward, rightFlowBackward;
    // With a shutter (camera.sensor.shutter_s, render/motion_blur.h), width*height: the left view's blur length in
    // pixels over the exposure, from the camera's motion and the exact depth (static geometry).
    std::vector<float> motionBlur;
    // With auto-exposure (camera.sensor.auto_exposure, render/auto_exposure.h): the frame's meter (the mean luminance
    // of the left colour before lens and sensor) and the exposure factor both views got; unset without.
    struct Exposure {
        double meter = 0.0, factor = 1.0;
    };
    std::optional<Exposure> autoExposure;
    // With camera.sensor.bit_depth (scene/sensor_raw.h), width*height*3 each: the views' digital numbers, R, G, B
    // (width*height with camera.sensor.bayer: the mosaic).
    std::vector<uint16_t> raw, rightRaw;
};

} // namespace sward
