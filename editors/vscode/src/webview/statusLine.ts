// The status line under the toolpath: its parts as separate items that wrap between each other (a
// short part never inside itself, a long one such as the machining time at its spaces) on three
// lines of a fixed height, so that the drawing above does not change its size (and refit) whenever
// the text changes; the whole text is its tooltip for when it has to be cut.

/** Parts longer than this many characters may wrap inside themselves. */
const LONG_PART = 40;

/** Shows `parts` in `element`, separated by ` · ` (so that its text reads as one line). */
export function showStatus(element: HTMLElement, parts: string[]): void {
  const text = parts.join(' · ');
  if (element.textContent === text) return;
  element.replaceChildren();
  parts.forEach((part, index) => {
    if (index > 0) element.append(' · ');
    const item = document.createElement('span');
    item.className = part.length > LONG_PART ? 'part long' : 'part';
    item.textContent = part;
    element.append(item);
  });
  element.title = text;
}
