// The player bar's play/pause button plays the generated clip in the page's <audio>. What the
// bar shows (position, progress) comes from the server on the simulated clock; this only makes
// the music audible. Regions are swapped by live pushes, so the handler is delegated.
document.addEventListener("click", (event) => {
  const toggle = event.target.closest("[data-player-toggle]");
  if (!toggle) return;
  const audio = document.querySelector("[data-player-audio]");
  if (!audio) return;
  if (audio.paused) {
    audio.play().catch(() => {});
  } else {
    audio.pause();
  }
});
