// The machining time of a program as the server estimates it (reference §15): the preview's
// top-level `time` / `program_time` and `sinumerik/modalState`'s `time`, all
// `{total_s, feed_s, rapid_s, dwell_s, unknown_moves}`. The total sums the moves whose time is known;
// when some are unknown (no feed, no spindle speed, an unknown position) it is a lower bound.

export interface ProgramTime {
  totalS: number;
  feedS: number;
  rapidS: number;
  dwellS: number;
  unknownMoves: number;
}

function seconds(value: unknown): number | null {
  return typeof value === 'number' && Number.isFinite(value) && value >= 0 ? value : null;
}

/** Reads a time object; null when it is absent or malformed (an older server). */
export function parseProgramTime(value: unknown): ProgramTime | null {
  if (typeof value !== 'object' || value === null || Array.isArray(value)) return null;
  const record = value as Record<string, unknown>;
  const totalS = seconds(record.total_s);
  const feedS = seconds(record.feed_s);
  const rapidS = seconds(record.rapid_s);
  const dwellS = seconds(record.dwell_s);
  const unknown = record.unknown_moves;
  if (totalS === null || feedS === null || rapidS === null || dwellS === null) return null;
  if (typeof unknown !== 'number' || !Number.isInteger(unknown) || unknown < 0) return null;
  return { totalS, feedS, rapidS, dwellS, unknownMoves: unknown };
}

/** `9.4 s`, `2 min 3 s`, `1 h 2 min 3 s`. */
export function formatDuration(totalSeconds: number): string {
  if (!Number.isFinite(totalSeconds) || totalSeconds < 0) return '?';
  if (totalSeconds < 60) return `${Number(totalSeconds.toFixed(1))} s`;
  const whole = Math.round(totalSeconds);
  const hours = Math.floor(whole / 3600);
  const minutes = Math.floor(whole / 60) % 60;
  const rest = whole % 60;
  return hours > 0 ? `${hours} h ${minutes} min ${rest} s` : `${minutes} min ${rest} s`;
}

/** The short text of a total: `⏱ 2 min 3 s`, with `≥` when some moves' time is unknown. */
export function formatProgramTime(time: ProgramTime): string {
  return `⏱ ${time.unknownMoves > 0 ? '≥ ' : ''}${formatDuration(time.totalS)}`;
}

/** The longer words of a total, for a tooltip or the toolpath view's info line. */
export function describeProgramTime(time: ProgramTime): string {
  const parts = [
    `machining time ${time.unknownMoves > 0 ? 'at least ' : ''}${formatDuration(time.totalS)}`,
    `feed ${formatDuration(time.feedS)}`,
    `rapid ${formatDuration(time.rapidS)}`,
  ];
  if (time.dwellS > 0) parts.push(`dwell ${formatDuration(time.dwellS)}`);
  let text = parts.join(', ');
  if (time.unknownMoves > 0) {
    text += ` (${time.unknownMoves.toLocaleString('en')} moves of unknown time: no feed, spindle speed or position)`;
  }
  return text;
}
