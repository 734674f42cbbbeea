# Writes syntaxes/sinumerik.tmLanguage.json. The grammar is kept here as Python so that the regular
# expressions can be written without JSON escaping; run `python3 scripts/grammar-source.py` after a change.
import json
import pathlib

WORD_START = r"(?<![A-Za-z0-9_$])"
# After a value the next letter starts a new word (G0X10), so single-letter addresses may follow digits.
ADDRESS_START = r"(?<![A-Za-z_$])"

def words(*names):
    return r"(?i)\b(?:" + "|".join(names) + r")\b"

control = ["IF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "FOR", "TO", "ENDFOR", "REPEAT", "REPEATB", "UNTIL",
           "LOOP", "ENDLOOP", "CASE", "OF", "DEFAULT", "GOTO", "GOTOF", "GOTOB", "GOTOC", "GOTOS", "ENDLABEL",
           "RET", "M17", "PROC", "EXTERN", "CALL", "PCALL", "MCALL", "EXTCALL", "CALLPATH", "STOPRE",
           "SAVE", "SBLOF", "SBLON", "DISPLOF", "DISPLON", "WHEN", "WHENEVER", "EVERY", "DO", "ID", "IDS"]
declaration = ["DEF", "REDEF", "DEFINE", "AS", "VAR", "NCK", "CHAN", "SYNR", "SYNW", "SYNRW"]
types = ["INT", "REAL", "BOOL", "CHAR", "STRING", "AXIS", "FRAME"]
word_operators = ["AND", "OR", "NOT", "XOR", "B_AND", "B_OR", "B_XOR", "B_NOT", "DIV", "MOD"]
constants = ["TRUE", "FALSE"]
instructions = ["TRANS", "ATRANS", "ROT", "AROT", "ROTS", "AROTS", "RPL", "SCALE", "ASCALE", "MIRROR", "AMIRROR",
                "DIAMON", "DIAMOF", "DIAM90", "DIAMONA", "DIAMOFA", "DIAMCHAN", "DIAMCHANA",
                "TRAORI", "TRACYL", "TRANSMIT", "TRAANG", "TRAFOOF", "SUPA", "CIP", "CT", "CFC", "CFTCP", "CFIN",
                "SPOS", "SPOSA", "POS", "POSA", "FA", "AX", "FGROUP", "OFFN", "MSG", "SETAL", "WRITE"]
functions = ["SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN2", "SQRT", "POT", "LN", "EXP", "ABS", "TRUNC", "ROUND",
             "ROUNDUP", "BOUND", "MINVAL", "MAXVAL", "ITOR", "RTOI", "STRLEN", "SPRINT", "SUBSTR", "INDEX",
             "RINDEX", "MINDEX", "MATCH", "TOUPPER", "TOLOWER", "NUMBER", "ISNUMBER", "AXNAME", "AXSTRING",
             "CTRANS", "CROT", "CROTS", "CSCALE", "CMIRROR", "CFINE", "INVFRAME", "ADDFRAME", "ISVAR", "ISFILE",
             "ISAXIS"]
modifiers = ["ACP", "ACN", "AC", "IC", "DC", "DAC", "DIC", "RAC", "RIC", "CACP", "CACN", "CAC", "CIC", "CDC"]
multi_letter_addresses = ["CR", "AR", "AP", "RP", "TURN", "I1", "J1", "K1"]

grammar = {
    "$schema": "https://raw.githubusercontent.com/martinring/tmlanguage/master/tmlanguage.json",
    "name": "SINUMERIK NC",
    "scopeName": "source.sinumerik",
    "fileTypes": ["mpf", "spf", "MPF", "SPF"],
    "patterns": [
        {"include": "#block-start"},
        {"include": "#line"},
    ],
    "repository": {
        "block-start": {
            "comment": "Skip level, block number and label at the start of a block.",
            # The lookahead makes sure something is there: the match is never empty.
            "match": r"^\s*(?=/|(?i:N)\d|:\d|[A-Za-z_][A-Za-z0-9_]*:(?![=:]))(/\d?)?\s*((?i:N)\d+|:\d+)?\s*(?:([A-Za-z_][A-Za-z0-9_]*)(:)(?![=:]))?",
            "captures": {
                "1": {"name": "keyword.other.block-skip.sinumerik"},
                "2": {"name": "constant.other.block-number.sinumerik"},
                "3": {"name": "entity.name.label.sinumerik"},
                "4": {"name": "punctuation.separator.label.sinumerik"},
            },
        },
        "line": {
            "patterns": [
                {"include": "#comment"},
                {"include": "#string"},
                {"include": "#quoted-number"},
                {"include": "#system-variable"},
                {"include": "#modifier"},
                {"include": "#keywords"},
                {"include": "#g-code"},
                {"include": "#m-code"},
                {"include": "#r-parameter"},
                {"include": "#multi-letter-address"},
                {"include": "#axis"},
                {"include": "#address"},
                {"include": "#identifier"},
                {"include": "#number"},
                {"include": "#operator"},
                {"include": "#brackets"},
            ]
        },
        "comment": {
            "match": r";.*$",
            "name": "comment.line.semicolon.sinumerik",
        },
        "string": {
            "comment": "No escapes: a backslash is an ordinary character; a string ends at the end of its line.",
            "begin": "\"",
            "end": "\"|$",
            "beginCaptures": {"0": {"name": "punctuation.definition.string.begin.sinumerik"}},
            "endCaptures": {"0": {"name": "punctuation.definition.string.end.sinumerik"}},
            "name": "string.quoted.double.sinumerik",
        },
        "quoted-number": {
            "match": r"(?i)'(?:H[0-9A-F]+|B[01]+)'",
            "name": "constant.numeric.radix.sinumerik",
        },
        "system-variable": {
            "match": r"\$[A-Za-z_][A-Za-z0-9_]*",
            "name": "variable.language.system.sinumerik",
        },
        "modifier": {
            "comment": "=AC(..), =IC(..) and the other position modifiers.",
            "match": r"(=)\s*((?i:" + "|".join(modifiers) + r"))(?=\s*\()",
            "captures": {
                "1": {"name": "keyword.operator.assignment.sinumerik"},
                "2": {"name": "support.function.modifier.sinumerik"},
            },
        },
        "keywords": {
            "patterns": [
                {"match": words(*control), "name": "keyword.control.sinumerik"},
                {"match": words(*declaration), "name": "storage.modifier.sinumerik"},
                {"match": words(*types), "name": "storage.type.sinumerik"},
                {"match": words(*word_operators), "name": "keyword.operator.word.sinumerik"},
                {"match": words(*constants), "name": "constant.language.sinumerik"},
                {"match": words(*functions) + r"(?=\s*\()", "name": "support.function.builtin.sinumerik"},
                {"match": words(*instructions), "name": "support.function.instruction.sinumerik"},
            ]
        },
        "g-code": {
            "match": ADDRESS_START + r"((?i:G))(\d+)(?![\d.])",
            "captures": {"0": {"name": "keyword.other.g-code.sinumerik"}},
        },
        "m-code": {
            "match": ADDRESS_START + r"((?i:M))(\d{1,2}(?==)|\[)?(=?)(\d+)?",
            "captures": {"0": {"name": "keyword.other.m-code.sinumerik"}},
        },
        "r-parameter": {
            "match": ADDRESS_START + r"(?i:R)(?:\d+|(?=\[))",
            "name": "variable.parameter.r-parameter.sinumerik",
        },
        "multi-letter-address": {
            "match": WORD_START + r"((?i:" + "|".join(multi_letter_addresses) + r"))(?=\s*=)",
            "name": "variable.other.address.sinumerik",
        },
        "axis": {
            "comment": "An axis letter, with a numeric extension only when `=` follows (X1=10 is axis X1).",
            "match": ADDRESS_START + r"((?i:[XYZABCUVWIJKQE]))(\d{1,2}(?=\s*=))?(?=\s*[-+=.\d(])",
            "name": "variable.other.axis.sinumerik",
        },
        "address": {
            "comment": "Feed, spindle, tool, offset, auxiliary, subprogram number and repetition addresses.",
            "match": ADDRESS_START + r"((?i:[FSTDHLP]))(\d{1,2}(?=\s*=))?(?=\s*[-+=.\d\[])",
            "name": "keyword.other.address.sinumerik",
        },
        "identifier": {
            "comment": "Names start with two letters (or an underscore); a lone name is a call.",
            "match": r"(?<![A-Za-z0-9_$])[A-Za-z_][A-Za-z_][A-Za-z0-9_]*",
            "name": "variable.other.name.sinumerik",
        },
        "number": {
            "comment": "Names are matched before numbers, so digits here follow an address or an operator.",
            "match": r"(?:\d+\.?\d*|\.\d+)(?:(?i:EX)[-+]?\d+)?",
            "name": "constant.numeric.sinumerik",
        },
        "operator": {
            "patterns": [
                {"match": r"==|<>|<=|>=|<<|<|>", "name": "keyword.operator.comparison.sinumerik"},
                {"match": r"=", "name": "keyword.operator.assignment.sinumerik"},
                {"match": r"[-+*/]", "name": "keyword.operator.arithmetic.sinumerik"},
                {"match": r",", "name": "punctuation.separator.sinumerik"},
            ]
        },
        "brackets": {
            "match": r"[()\[\]]",
            "name": "punctuation.bracket.sinumerik",
        },
    },
}

target = pathlib.Path(__file__).resolve().parent.parent / "syntaxes" / "sinumerik.tmLanguage.json"
target.write_text(json.dumps(grammar, indent=2) + "\n")
print(f"wrote {target}")
