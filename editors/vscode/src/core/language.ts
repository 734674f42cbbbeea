// The language id of SINUMERIK programs in the editors (package.json contributes it).
export const LANGUAGE_ID = 'sinumerik';
