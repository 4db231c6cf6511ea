"""Drive, then record (docs/python.md, "Drive and record"): Simulator.record writes what the Python loop renders, tick
by tick, as a sward dataset; Simulator.drive steers a scene object as a vehicle (throttle, steer, brake)."""
import json
import numbers
import os

from . import _sward


def _argument_error(message):
    from . import ArgumentError  # the package's, which imports this module first
    return ArgumentError(message)


def _control(name, value, low):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a number, not {type(value).__name__}")
    if not low <= value <= 1:  # NaN fails too
        raise _argument_error(f"{name} must be a number from {low} to 1 (got {value})")
    return float(value)


class Recorder:
    """Writes every frame its Simulator renders from now on, as rendered, into the dataset folder `out` (the files
    sward-render writes; frames.jsonl with the poses and colliders that were used). close() (or leaving a `with`
    block) writes frames.jsonl, scene.json, classes.json, calib.txt and manifest.json. An episode is never resumed: a
    folder that holds a dataset is refused unless overwrite=True."""

    def __init__(self, sim, out, *, overwrite=False):
        if not isinstance(out, (str, os.PathLike)):
            raise TypeError(f"out must be a folder path (str or os.PathLike), not {type(out).__name__}")
        if not isinstance(overwrite, bool):
            raise TypeError(f"overwrite must be True or False, not {type(overwrite).__name__}")
        path, text, overrides, seed, allow = sim._input
        _device, _validation, vegetation, time = sim._options
        self.out = os.fspath(out)
        self._recorder = _sward.EpisodeRecorder(sim._live(), path, text, overrides, seed, allow, vegetation, time,
                                                self.out, overwrite)

    @property
    def frames(self):
        """The frames recorded so far, in order."""
        return list(self._recorder.frames)

    @property
    def closed(self):
        return self._recorder.closed

    def close(self):
        """Writes the per-dataset files and the manifest and stops recording; a second call does nothing."""
        self._recorder.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()  # the frames recorded before an exception are a dataset too
        return False

    def __repr__(self):
        state = "closed" if self.closed else "recording"
        return f"<sward.Recorder {self.out!r}: {len(self._recorder.frames)} frame(s), {state}>"


class DriveAndRecord:
    """Simulator's closed-loop methods (a base class of sward.Simulator)."""

    def record(self, out, *, overwrite=False):
        """A Recorder writing every frame render() returns from now on into the dataset folder `out`."""
        return Recorder(self, out, overwrite=overwrite)

    def drive(self, vehicle=0, *, throttle=0.0, steer=0.0, brake=0.0):
        """Drives scene object `vehicle` one tick (sequence.time_step) with a kinematic bicycle model: throttle -1..1,
        steer -1 (right) .. 1 (left), brake 0..1. Call once per tick before render() / step(1); returns the new state
        {"position": (x, y), "heading_deg", "speed"}."""
        if isinstance(vehicle, bool) or not isinstance(vehicle, numbers.Integral):
            raise TypeError(f"vehicle must be an integer (a scene object's index), not {type(vehicle).__name__}")
        if vehicle < 0:
            raise _argument_error(f"vehicle must be a scene object's index, 0 or more (got {vehicle})")
        return _sward.drive(self._live(), int(vehicle), _control("throttle", throttle, -1),
                            _control("steer", steer, -1), _control("brake", brake, 0))

    def set_wind(self, **keys):
        """The scene's wind from the next frame on: keys as in a scene file's "wind" (direction_deg, strength,
        gust_strength, gust_frequency, gust_wavelength, flutter); those not given keep their values."""
        self._set_weather("wind", keys)

    def set_sun(self, **keys):
        """The sun from the next frame on: azimuth_deg, elevation_deg, radiance [r, g, b] (a scene file's "sun")."""
        self._set_weather("sun", keys)

    def set_sky(self, **keys):
        """The sky from the next frame on: a scene file's "sky" keys (model, turbidity, clouds, visibility_m, zenith,
        horizon, ground); the model stays unless given (or implied by zenith / horizon)."""
        self._set_weather("sky", keys)

    def _set_weather(self, section, keys):
        from . import _json  # the package's checked JSON encoding (NaN and non-JSON values named)
        _sward.set_weather(self._live(), section, _json(f"set_{section}", keys))

    def reset(self, *, seed=None, overrides=None):
        """A new episode on the same device and buffers. Without arguments: the scene as built (camera, objects, wind,
        sun and sky as loaded, no colliders of yours, no driven vehicle) with the interaction at rest, frame 0. With
        `seed` and / or `overrides` (dotted keys added to the constructor's): that scene, built anew on the device
        already open. Either way the frames that follow are a new Simulator's, bitwise."""
        from . import _scene_input  # the package's argument checks
        session = self._live()
        if seed is None and overrides is None:
            _sward.reset(session, True, *self._input)
            return
        path, text, old_overrides, old_seed, folders = self._input
        if overrides is not None and not isinstance(overrides, dict):
            raise TypeError('overrides must be a dict of dotted keys, e.g. {"render.samples": 1}')
        merged = {**json.loads(old_overrides), **(overrides or {})}
        _, _, merged_text, seed, _ = _scene_input(None, merged, old_seed if seed is None else seed, ())
        new_input = (path, text, merged_text, seed, folders)
        _sward.reset(session, False, *new_input)
        self._input = new_input
