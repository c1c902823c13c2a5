"""Generated audio: a short, small, valid WAV per slug — the same slug gives the same bytes,
different slugs different tunes — served at /media/audio/<slug>.wav with immutable caching."""

from __future__ import annotations

import io
import wave

from django.test import Client

from apps.media import audio, links


def opened(body: bytes) -> wave.Wave_read:
    return wave.open(io.BytesIO(body), "rb")


def test_a_clip_is_a_short_small_mono_wav():
    body = audio.clip("restless-freeways").body
    clip = opened(body)
    assert (clip.getnchannels(), clip.getsampwidth(), clip.getframerate()) == (1, 1, audio.RATE)
    seconds = clip.getnframes() / clip.getframerate()
    assert 3 <= seconds <= 20
    assert len(body) < 200_000


def test_the_same_slug_gives_the_same_bytes_and_different_slugs_differ():
    first = audio.wav(links.seeded_random("microfy-track-001"))
    assert first == audio.wav(links.seeded_random("microfy-track-001"))
    assert first != audio.wav(links.seeded_random("microfy-track-002"))


def test_a_clip_is_music_not_silence_and_never_clips_out_of_range():
    frames = opened(audio.clip("microfy-track-001").body).readframes(audio.RATE)
    assert max(frames) - min(frames) > 100  # an audible tune
    assert len(set(frames)) > 50


def test_clips_are_served_with_immutable_caching_and_an_etag():
    client = Client()
    assert links.audio_url("MicroFy track-001") == "/media/audio/microfy-track-001.wav"
    response = client.get("/media/audio/microfy-track-001.wav")
    assert response.status_code == 200
    assert response["Content-Type"] == "audio/wav"
    assert response["Cache-Control"] == "public, max-age=31536000, immutable"
    again = client.get("/media/audio/microfy-track-001.wav", HTTP_IF_NONE_MATCH=response["ETag"])
    assert again.status_code == 304
    assert client.get("/media/audio/Bad%20Slug.wav").status_code == 404
