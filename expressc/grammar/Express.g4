// SPDX-License-Identifier: Apache-2.0
// EXPRESS (ISO 10303-11:2004), syntax only.
//
// The grammar follows the syntax of the standard's annex A, with one
// deliberate simplification: the standard distinguishes entity_ref, type_ref,
// attribute_ref, ... which are all plain identifiers and can only be told
// apart by name resolution. Here they are all `name`, and the resolver
// (expressc/model) decides what each one means. Likewise the concrete and
// generalized type grammars share one `typeSpec`; where only a concrete type
// is allowed, the parse tree builder reports the generalized forms.
//
// Keywords are case-insensitive (fragment letters, since ANTLR 4.7.2 has no
// caseInsensitive option). Built-in functions, procedures and constants
// (ABS, SIZEOF, INSERT, PI, ...) are identifiers here and are recognised by
// the resolver.
grammar Express;

// ----------------------------------------------------------------- schemas

syntaxFile : schemaDecl* EOF ;

schemaDecl
    : SCHEMA name STRING_LITERAL? ';' schemaBody END_SCHEMA ';'
    ;

schemaBody : interfaceSpec* constantDecl? schemaItem* ;

schemaItem : declaration | ruleDecl ;

interfaceSpec
    : kind=(USE | REFERENCE) FROM name ('(' interfaceItem (',' interfaceItem)* ')')? ';'
    ;

interfaceItem : name (AS alias=name)? ;

constantDecl : CONSTANT constantBody+ END_CONSTANT ';' ;

constantBody : name ':' typeSpec ':=' expression ';' ;

declaration
    : entityDecl
    | functionDecl
    | procedureDecl
    | subtypeConstraintDecl
    | typeDecl
    ;

// ----------------------------------------------------------------- types

typeDecl : TYPE name '=' underlyingType ';' whereClause? END_TYPE ';' ;

underlyingType : enumerationType | selectType | typeSpec ;

enumerationType
    : EXTENSIBLE? ENUMERATION (OF nameList | BASED_ON basedOn=name (WITH nameList)?)?
    ;

selectType
    : (EXTENSIBLE GENERIC_ENTITY?)? SELECT (nameList | BASED_ON basedOn=name (WITH nameList)?)?
    ;

nameList : '(' name (',' name)* ')' ;

// Every type that can be written after ':' (attributes, parameters, locals,
// constants, aggregate elements) or after '=' in a TYPE declaration.
typeSpec
    : simpleType                                                   # simpleTypeSpec
    | name                                                         # namedTypeSpec
    | ARRAY boundSpec? OF OPTIONAL? UNIQUE? typeSpec               # arrayTypeSpec
    | LIST boundSpec? OF UNIQUE? typeSpec                          # listTypeSpec
    | BAG boundSpec? OF typeSpec                                   # bagTypeSpec
    | SET boundSpec? OF typeSpec                                   # setTypeSpec
    | AGGREGATE (':' label=name)? OF typeSpec                      # aggregateTypeSpec
    | GENERIC (':' label=name)?                                    # genericTypeSpec
    | GENERIC_ENTITY (':' label=name)?                             # genericEntityTypeSpec
    ;

simpleType
    : kind=(BINARY | STRING) ('(' width=expression ')' FIXED?)?
    | kind=REAL ('(' width=expression ')')?
    | kind=(BOOLEAN | INTEGER | LOGICAL | NUMBER)
    ;

boundSpec : '[' lower=expression ':' upper=expression ']' ;

// ----------------------------------------------------------------- entities

entityDecl
    : ENTITY name supertypeConstraint? subtypeDecl? ';'
      explicitAttr*
      deriveClause?
      inverseClause?
      uniqueClause?
      whereClause?
      END_ENTITY ';'
    ;

supertypeConstraint
    : ABSTRACT SUPERTYPE (OF '(' supertypeExpression ')')?
    | ABSTRACT
    | SUPERTYPE OF '(' supertypeExpression ')'
    ;

supertypeExpression : supertypeFactor (ANDOR supertypeFactor)* ;

supertypeFactor : supertypeTerm (AND supertypeTerm)* ;

supertypeTerm
    : name
    | ONEOF '(' supertypeExpression (',' supertypeExpression)* ')'
    | '(' supertypeExpression ')'
    ;

subtypeDecl : SUBTYPE OF nameList ;

explicitAttr : attributeDecl (',' attributeDecl)* ':' OPTIONAL? typeSpec ';' ;

// `name`, or a redeclaration `SELF\supertype.attribute [RENAMED name]`.
attributeDecl : name | qualifiedAttribute (RENAMED renamed=name)? ;

qualifiedAttribute : SELF '\\' entity=name '.' attribute=name ;

deriveClause : DERIVE derivedAttr+ ;

derivedAttr : attributeDecl ':' typeSpec ':=' expression ';' ;

inverseClause : INVERSE inverseAttr+ ;

inverseAttr
    : attributeDecl ':' (aggregate=(SET | BAG) boundSpec? OF)? entity=name
      FOR (forEntity=name '.')? forAttribute=name ';'
    ;

uniqueClause : UNIQUE (uniqueRule ';')+ ;

uniqueRule : (label=name ':')? referencedAttribute (',' referencedAttribute)* ;

referencedAttribute : name | qualifiedAttribute ;

whereClause : WHERE (domainRule ';')+ ;

domainRule : (label=name ':')? expression ;

subtypeConstraintDecl
    : SUBTYPE_CONSTRAINT name FOR entity=name ';'
      (ABSTRACT SUPERTYPE ';')?
      (TOTAL_OVER nameList ';')?
      (supertypeExpression ';')?
      END_SUBTYPE_CONSTRAINT ';'
    ;

// ----------------------------------------------------------------- algorithms

functionDecl
    : FUNCTION name ('(' formalParameter (';' formalParameter)* ')')? ':' typeSpec ';'
      algorithmHead
      statement+
      END_FUNCTION ';'
    ;

procedureDecl
    : PROCEDURE name ('(' procedureParameter (';' procedureParameter)* ')')? ';'
      algorithmHead
      statement*
      END_PROCEDURE ';'
    ;

formalParameter : name (',' name)* ':' typeSpec ;

procedureParameter : VAR? formalParameter ;

ruleDecl
    : RULE name FOR nameList ';'
      algorithmHead
      statement*
      whereClause
      END_RULE ';'
    ;

algorithmHead : declaration* constantDecl? localDecl? ;

localDecl : LOCAL localVariable+ END_LOCAL ';' ;

localVariable : name (',' name)* ':' typeSpec (':=' expression)? ';' ;

// ----------------------------------------------------------------- statements

statement
    : ALIAS name FOR target=reference ';' statement+ END_ALIAS ';'                 # aliasStatement
    | target=reference ':=' expression ';'                                        # assignmentStatement
    | CASE selector=expression OF caseAction* (OTHERWISE ':' otherwise=statement)? END_CASE ';' # caseStatement
    | BEGIN statement+ END ';'                                                    # compoundStatement
    | ESCAPE ';'                                                                  # escapeStatement
    | IF expression THEN thenBranch ( ELSE elseBranch )? END_IF ';'               # ifStatement
    | ';'                                                                         # nullStatement
    | name actualParameters? ';'                                                  # callStatement
    | REPEAT repeatControl ';' statement+ END_REPEAT ';'                          # repeatStatement
    | RETURN ('(' expression ')')? ';'                                            # returnStatement
    | SKIP_ ';'                                                                   # skipStatement
    ;

thenBranch : statement+ ;
elseBranch : statement+ ;

// An assignable or aliasable reference: a variable or parameter with
// qualifiers, e.g. `result[i].x`.
reference : (name | SELF) qualifier* ;

caseAction : caseLabel (',' caseLabel)* ':' statement ;
caseLabel : expression ;

repeatControl
    : (variable=name ':=' from=expression TO to=expression (BY by=expression)?)?
      (WHILE whileCondition=expression)?
      (UNTIL untilCondition=expression)?
    ;

// ----------------------------------------------------------------- expressions
// Precedence, lowest first: relational, additive, multiplicative, power,
// unary, qualified primary (ISO 10303-11 table 11).

expression : left=simpleExpression (op=relationalOperator right=simpleExpression)? ;

relationalOperator
    : '<' | '>' | '<=' | '>=' | '<>' | '=' | ':<>:' | ':=:' | IN | LIKE
    ;

simpleExpression : term (addOperator term)* ;

addOperator : '+' | '-' | OR | XOR ;

term : factor (multiplyOperator factor)* ;

multiplyOperator : '*' | '/' | DIV | MOD | AND | '||' ;

factor : simpleFactor ('**' exponent=simpleFactor)? ;

simpleFactor : unaryOperator? primary ;

unaryOperator : '+' | '-' | NOT ;

primary : atom qualifier* ;

atom
    : literal                                                                   # literalAtom
    | '?'                                                                       # indeterminateAtom
    | SELF                                                                      # selfAtom
    | '(' expression ')'                                                        # parenthesizedAtom
    | '[' (aggregateElement (',' aggregateElement)*)? ']'                       # aggregateAtom
    | '{' low=simpleExpression lowOp=intervalOperator item=simpleExpression
          highOp=intervalOperator high=simpleExpression '}'                     # intervalAtom
    | QUERY '(' variable=name '<*' source=expression '|' condition=expression ')' # queryAtom
    | TREAT '(' operand=expression AS target=name ')'                           # treatAtom
    | name actualParameters?                                                    # nameAtom
    ;

aggregateElement : expression (':' repetition=expression)? ;

intervalOperator : '<' | '<=' ;

actualParameters : '(' (expression (',' expression)*)? ')' ;

qualifier
    : '.' name                                                                  # attributeQualifier
    | '\\' name                                                                 # groupQualifier
    | '[' index=simpleExpression (':' indexHigh=simpleExpression)? ']'          # indexQualifier
    ;

literal
    : INTEGER_LITERAL
    | REAL_LITERAL
    | STRING_LITERAL
    | ENCODED_STRING_LITERAL
    | BINARY_LITERAL
    | TRUE
    | FALSE
    | UNKNOWN
    ;

// TREAT (the type narrowing of the EXPRESS edition 3 drafts, not in
// ISO 10303-11:2004) is a token of its own so that only it needs the
// lookahead that tells `TREAT(x AS t)` from a call, but no reserved word:
// a schema may still name something `treat`.
name : IDENTIFIER | TREAT ;

// ----------------------------------------------------------------- lexer

ABSTRACT : A B S T R A C T ;
AGGREGATE : A G G R E G A T E ;
ALIAS : A L I A S ;
AND : A N D ;
ANDOR : A N D O R ;
ARRAY : A R R A Y ;
AS : A S ;
BAG : B A G ;
BASED_ON : B A S E D '_' O N ;
BEGIN : B E G I N ;
BINARY : B I N A R Y ;
BOOLEAN : B O O L E A N ;
BY : B Y ;
CASE : C A S E ;
CONSTANT : C O N S T A N T ;
DERIVE : D E R I V E ;
DIV : D I V ;
ELSE : E L S E ;
END : E N D ;
END_ALIAS : E N D '_' A L I A S ;
END_CASE : E N D '_' C A S E ;
END_CONSTANT : E N D '_' C O N S T A N T ;
END_ENTITY : E N D '_' E N T I T Y ;
END_FUNCTION : E N D '_' F U N C T I O N ;
END_IF : E N D '_' I F ;
END_LOCAL : E N D '_' L O C A L ;
END_PROCEDURE : E N D '_' P R O C E D U R E ;
END_REPEAT : E N D '_' R E P E A T ;
END_RULE : E N D '_' R U L E ;
END_SCHEMA : E N D '_' S C H E M A ;
END_SUBTYPE_CONSTRAINT : E N D '_' S U B T Y P E '_' C O N S T R A I N T ;
END_TYPE : E N D '_' T Y P E ;
ENTITY : E N T I T Y ;
ENUMERATION : E N U M E R A T I O N ;
ESCAPE : E S C A P E ;
EXTENSIBLE : E X T E N S I B L E ;
FALSE : F A L S E ;
FIXED : F I X E D ;
FOR : F O R ;
FROM : F R O M ;
FUNCTION : F U N C T I O N ;
GENERIC : G E N E R I C ;
GENERIC_ENTITY : G E N E R I C '_' E N T I T Y ;
IF : I F ;
IN : I N ;
INTEGER : I N T E G E R ;
INVERSE : I N V E R S E ;
LIKE : L I K E ;
LIST : L I S T ;
LOCAL : L O C A L ;
LOGICAL : L O G I C A L ;
MOD : M O D ;
NOT : N O T ;
NUMBER : N U M B E R ;
OF : O F ;
ONEOF : O N E O F ;
OPTIONAL : O P T I O N A L ;
OR : O R ;
OTHERWISE : O T H E R W I S E ;
PROCEDURE : P R O C E D U R E ;
QUERY : Q U E R Y ;
REAL : R E A L ;
REFERENCE : R E F E R E N C E ;
RENAMED : R E N A M E D ;
REPEAT : R E P E A T ;
RETURN : R E T U R N ;
RULE : R U L E ;
SCHEMA : S C H E M A ;
SELECT : S E L E C T ;
SELF : S E L F ;
SET : S E T ;
SKIP_ : S K I P ;
STRING : S T R I N G ;
SUBTYPE : S U B T Y P E ;
SUBTYPE_CONSTRAINT : S U B T Y P E '_' C O N S T R A I N T ;
SUPERTYPE : S U P E R T Y P E ;
THEN : T H E N ;
TO : T O ;
TOTAL_OVER : T O T A L '_' O V E R ;
TREAT : T R E A T ;
TRUE : T R U E ;
TYPE : T Y P E ;
UNIQUE : U N I Q U E ;
UNKNOWN : U N K N O W N ;
UNTIL : U N T I L ;
USE : U S E ;
VAR : V A R ;
WHERE : W H E R E ;
WHILE : W H I L E ;
WITH : W I T H ;
XOR : X O R ;

IDENTIFIER : [a-zA-Z] [a-zA-Z0-9_]* ;

REAL_LITERAL
    : [0-9]+ '.' [0-9]* EXPONENT?
    | [0-9]+ EXPONENT
    ;
INTEGER_LITERAL : [0-9]+ ;
fragment EXPONENT : [eE] [+-]? [0-9]+ ;

STRING_LITERAL : '\'' ( '\'\'' | ~'\'' )* '\'' ;
ENCODED_STRING_LITERAL : '"' [0-9a-fA-F]* '"' ;
BINARY_LITERAL : '%' [01]+ ;

// Embedded remarks nest; a tail remark runs to the end of the line.
EMBEDDED_REMARK : '(*' ( EMBEDDED_REMARK | . )*? '*)' -> skip ;
TAIL_REMARK : '--' ~[\r\n]* -> skip ;
WHITESPACE : [ \t\r\n\f]+ -> skip ;

// Anything else becomes a token the parser rejects with a clear position.
UNEXPECTED_CHARACTER : . ;

fragment A : [aA] ; fragment B : [bB] ; fragment C : [cC] ; fragment D : [dD] ;
fragment E : [eE] ; fragment F : [fF] ; fragment G : [gG] ; fragment H : [hH] ;
fragment I : [iI] ; fragment J : [jJ] ; fragment K : [kK] ; fragment L : [lL] ;
fragment M : [mM] ; fragment N : [nN] ; fragment O : [oO] ; fragment P : [pP] ;
fragment Q : [qQ] ; fragment R : [rR] ; fragment S : [sS] ; fragment T : [tT] ;
fragment U : [uU] ; fragment V : [vV] ; fragment W : [wW] ; fragment X : [xX] ;
fragment Y : [yY] ; fragment Z : [zZ] ;
