" Highlighting for SINUMERIK NC programs: comments, strings, block numbers, labels, G and M codes,
" axis words, position modifiers, R parameters, system variables and keywords (case-insensitive).
if exists('b:current_syntax')
  finish
endif
syntax case ignore

syntax match sinumerikNumber /\v\d+\.?\d*(ex[-+]?\d+)?|\.\d+(ex[-+]?\d+)?/
syntax match sinumerikRadix /\v'(h[0-9a-f]+|b[01]+)'/
syntax match sinumerikAxis /\v(<|\d)@<=[xyzabcuvwijkqe](\d{1,2}\s*\=)@=|(<|\d)@<=[xyzabcuvwijkqe]([-+=.0-9(])@=/
syntax match sinumerikAddress /\v(<|\d)@<=[fstdhlp]([-+=.0-9\[])@=/
syntax match sinumerikGCode /\v(<|\d)@<=g\d+/
syntax match sinumerikMCode /\v(<|\d)@<=m(\d{1,2}\=)?\d+/
syntax match sinumerikRParameter /\v(<|\d)@<=r(\d+|\[@=)/
syntax match sinumerikSystemVariable /\v\$[a-z_][a-z0-9_]*/
syntax match sinumerikModifier /\v\=@<=\s*(acp|acn|ac|ic|dc|dac|dic|rac|ric|cacp|cacn|cac|cic|cdc)\s*\(@=/
syntax match sinumerikBlockNumber /\v^\s*(\/\d?\s*)?(n\d+|:\d+)/
syntax match sinumerikLabel /\v^\s*(\/\d?\s*)?(n\d+\s+)?[a-z_][a-z0-9_]*:(\=)@!/
syntax keyword sinumerikControl if else endif while endwhile for to endfor repeat repeatb until loop endloop
syntax keyword sinumerikControl case of default goto gotof gotob gotoc gotos ret proc extern call pcall mcall
syntax keyword sinumerikControl save sblof displof stopre when whenever every do
syntax keyword sinumerikDeclaration def redef define as var
syntax keyword sinumerikType int real bool char string axis frame
syntax keyword sinumerikOperator and or not xor b_and b_or b_xor b_not div mod
syntax keyword sinumerikInstruction trans atrans rot arot rots arots scale ascale mirror amirror diamon diamof diam90
syntax keyword sinumerikInstruction traori tracyl transmit trafoof supa cip ct msg setal
syntax region sinumerikString start=/"/ end=/"\|$/ oneline
syntax match sinumerikComment /;.*$/ contains=@Spell

highlight default link sinumerikComment Comment
highlight default link sinumerikString String
highlight default link sinumerikNumber Number
highlight default link sinumerikRadix Number
highlight default link sinumerikBlockNumber LineNr
highlight default link sinumerikLabel Label
highlight default link sinumerikGCode Statement
highlight default link sinumerikMCode PreProc
highlight default link sinumerikAxis Identifier
highlight default link sinumerikAddress Type
highlight default link sinumerikRParameter Special
highlight default link sinumerikSystemVariable Constant
highlight default link sinumerikModifier Function
highlight default link sinumerikControl Keyword
highlight default link sinumerikDeclaration StorageClass
highlight default link sinumerikType Type
highlight default link sinumerikOperator Operator
highlight default link sinumerikInstruction Function

let b:current_syntax = 'sinumerik'
