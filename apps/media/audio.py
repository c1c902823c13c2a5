"""Short generated music: a deterministic WAV clip per slug, written with the standard library.

A track's clip is a little melody (a pentatonic tune over a bass note and a soft kick) whose key,
tempo and notes come from the slug's seeded randomness, so the same slug always gives the same
bytes. 8 kHz, mono, 8-bit and ten seconds long: about 80 KB, enough for a player to play.
"""

from __future__ import annotations

import array
import functools
import io
import math
import random
import wave

from apps.media.images import Image, tagged
from apps.media.links import seeded_random

RATE = 8000  # samples a second
SECONDS = 10.0
PENTATONIC = (0, 2, 4, 7, 9, 12, 14, 16)  # semitones above the key
CLIPS_KEPT = 256


@functools.lru_cache(maxsize=CLIPS_KEPT)
def clip(slug: str) -> Image:
    """The WAV file of `slug` with its ETag (made once per process)."""
    return tagged(wav(seeded_random(slug)))


def wav(rng: random.Random) -> bytes:
    samples = melody(rng)
    out = io.BytesIO()
    with wave.open(out, "wb") as file:
        file.setnchannels(1)
        file.setsampwidth(1)  # 8-bit unsigned
        file.setframerate(RATE)
        file.writeframes(samples.tobytes())
    return out.getvalue()


def _frequency(semitones_above_a3: float) -> float:
    return 220.0 * 2 ** (semitones_above_a3 / 12)


def melody(rng: random.Random) -> array.array:
    """The clip's samples as unsigned bytes (silence is 128)."""
    key = rng.randrange(-5, 7)
    beat = 60.0 / rng.uniform(84, 128)
    notes = [rng.choice(PENTATONIC) for _ in range(8)]  # a one-bar motif, repeated with variations
    total = int(RATE * SECONDS)
    mix = [0.0] * total
    t, index = 0.0, 0
    while t < SECONDS:
        pitch = notes[index % len(notes)] + (12 if index // 8 % 2 and rng.random() < 0.3 else 0)
        length = beat / 2 if rng.random() < 0.7 else beat
        _tone(mix, t, length * 0.95, _frequency(key + pitch), 0.32)
        if index % 2 == 0:
            _tone(mix, t, beat * 0.9, _frequency(key - 12 + (0 if index % 8 < 4 else 5)), 0.22)
            _kick(mix, t)
        t += length
        index += 1
    return array.array("B", (max(0, min(255, int(128 + 127 * v))) for v in mix))


def _tone(mix: list[float], start: float, length: float, frequency: float, volume: float) -> None:
    """A plucked note: a sine with its octave, a quick attack and an exponential decay."""
    first, count = int(start * RATE), int(length * RATE)
    step = 2 * math.pi * frequency / RATE
    for n in range(min(count, len(mix) - first)):
        envelope = min(1.0, n / 80) * math.exp(-3.0 * n / count)
        mix[first + n] += volume * envelope * (math.sin(step * n) + 0.3 * math.sin(2 * step * n))


def _kick(mix: list[float], start: float) -> None:
    first = int(start * RATE)
    for n in range(min(int(0.12 * RATE), len(mix) - first)):
        frequency = 110 * math.exp(-n / 300) + 40
        mix[first + n] += 0.3 * math.exp(-n / 400) * math.sin(2 * math.pi * frequency * n / RATE)
